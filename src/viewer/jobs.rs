//! Background work of the viewer: workers on their own threads (sharing the window's GPU
//! device) report progress through channels that the UI polls every frame, and stop when
//! asked; the UI thread never waits for them (only the end of a run does, for a bounded
//! time: [`wait_for_workers`]). The shadow profile's worker is here, the radiosity's in
//! [`super::live_radiosity`].

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc::{channel, Receiver, Sender};
use std::sync::Arc;

use crate::geometry::Mesh;
use crate::gpu::Gpu;
use crate::scene::Camera;
use crate::study::shadow_profile::{compute_on, prepare, Profile, ProfileError, ProfileSpec};
use crate::study::view_hours::{compute as view_hours, ViewHours};

/// Flags a worker reads between units of work.
#[derive(Debug, Default)]
pub struct JobControl {
    /// Stop as soon as possible (results so far are kept by the UI).
    pub cancel: AtomicBool,
    /// Hold between units of work until cleared.
    pub pause: AtomicBool,
    /// Set by the worker while it holds for `pause` (the unit under way has ended), so a
    /// pause can show "pausing…" until then.
    pub holding: AtomicBool,
}

/// Worker threads of this process that have not ended yet.
static RUNNING: AtomicUsize = AtomicUsize::new(0);

/// Counts a worker thread as running until it is dropped (when the thread ends, also by a
/// panic).
struct Running;

impl Running {
    fn start() -> Running {
        RUNNING.fetch_add(1, Ordering::SeqCst);
        Running
    }
}

impl Drop for Running {
    fn drop(&mut self) {
        RUNNING.fetch_sub(1, Ordering::SeqCst);
    }
}

/// Waits until every worker thread has ended, at most `limit`; true when they have. A
/// process that exits while a worker is inside the GPU driver can crash there (NVIDIA's
/// Vulkan driver does), so a run cancels its workers and waits here before returning.
pub fn wait_for_workers(limit: std::time::Duration) -> bool {
    let until = std::time::Instant::now() + limit;
    while RUNNING.load(Ordering::SeqCst) > 0 {
        if std::time::Instant::now() >= until {
            return false;
        }
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    true
}

/// A worker thread sending updates of type `U`.
pub struct Worker<U> {
    /// Its flags.
    pub control: Arc<JobControl>,
    updates: Receiver<U>,
    finished: bool,
}

impl<U: Send + 'static> Worker<U> {
    /// Starts `work` on a new thread; it sends updates and reads the flags.
    pub fn spawn(
        name: &str,
        work: impl FnOnce(Sender<U>, Arc<JobControl>) + Send + 'static,
    ) -> std::io::Result<Worker<U>> {
        let control = Arc::new(JobControl::default());
        let (tx, rx) = channel();
        let flags = control.clone();
        let running = Running::start();
        std::thread::Builder::new()
            .name(name.into())
            .spawn(move || {
                let _running = running;
                work(tx, flags)
            })?;
        Ok(Worker {
            control,
            updates: rx,
            finished: false,
        })
    }

    /// Every update sent since the last call (never blocks).
    pub fn poll(&mut self) -> Vec<U> {
        let mut out = Vec::new();
        loop {
            match self.updates.try_recv() {
                Ok(u) => out.push(u),
                Err(std::sync::mpsc::TryRecvError::Empty) => break,
                Err(std::sync::mpsc::TryRecvError::Disconnected) => {
                    self.finished = true;
                    break;
                }
            }
        }
        out
    }

    /// Whether the thread has ended (and every update was polled).
    pub fn finished(&self) -> bool {
        self.finished
    }

    /// Asks the thread to stop (it ends on its own; nothing waits for it).
    pub fn cancel(&self) {
        self.control.cancel.store(true, Ordering::SeqCst);
        self.control.pause.store(false, Ordering::SeqCst);
    }
}

impl<U> Drop for Worker<U> {
    fn drop(&mut self) {
        self.control.cancel.store(true, Ordering::SeqCst);
    }
}

/// A profile worker's report.
pub enum ProfileUpdate {
    /// Steps done of the total.
    Progress(usize, usize),
    /// The profile.
    Done(Box<Profile>),
    /// The hours of sun on the model from the camera the job was started with.
    View(Box<ViewHours>),
    /// Cancelled or failed.
    Failed(String),
}

/// Starts a shadow profile of `mesh` on `gpu`, then, with `view` (a perspective camera
/// and an image size), the hours of sun on the model seen from it.
pub fn start_profile(
    gpu: Arc<Gpu>,
    mesh: Mesh,
    spec: ProfileSpec,
    view: Option<(Camera, (u32, u32))>,
) -> std::io::Result<Worker<ProfileUpdate>> {
    Worker::spawn("shadow profile", move |tx, control| {
        let parts = 1 + view.is_some() as usize;
        let progress = |part: usize| {
            let tx = tx.clone();
            move |done, total| {
                let _ = tx.send(ProfileUpdate::Progress(part * total + done, parts * total));
            }
        };
        let failed = |e: ProfileError| match e {
            ProfileError::Cancelled => ProfileUpdate::Failed("cancelled".into()),
            e => ProfileUpdate::Failed(e.to_string()),
        };
        let profile = prepare(&gpu, &mesh).and_then(|geometry| {
            compute_on(&gpu, &geometry, &spec, progress(0), &control.cancel).map(|p| (p, geometry))
        });
        let geometry = match profile {
            Ok((p, geometry)) => {
                let _ = tx.send(ProfileUpdate::Done(Box::new(p)));
                geometry
            }
            Err(e) => return drop(tx.send(failed(e))),
        };
        if let Some((camera, size)) = view {
            let v = view_hours(
                &gpu,
                &geometry,
                &spec,
                &camera,
                size,
                progress(1),
                &control.cancel,
            );
            let _ = tx.send(match v {
                Ok(v) => ProfileUpdate::View(Box::new(v)),
                Err(e) => failed(e),
            });
        }
    })
}
