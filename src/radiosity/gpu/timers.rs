//! The GPU's own clock around the solver's batches (`bench radiosity`): timestamps at the
//! start and end of each batch's visibility render pass and receive compute pass, so a
//! benchmark says whether a real GPU's time goes into drawing the maps or into the
//! receivers, which the wall clock on the CPU cannot tell apart.

use crate::gpu::{Gpu, GpuError};

/// Seconds the GPU spent in the solver's passes, by the GPU's timestamps.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct GpuPassSeconds {
    /// The visibility render passes (each tile's clear and the mesh's draws).
    pub maps: f64,
    /// The receive compute passes (one dispatch per map over the batch's receivers).
    pub receive: f64,
    /// Passes of each kind timed.
    pub batches: u64,
}

/// Queries per batch: map pass start and end, receive pass start and end.
const PER_BATCH: u32 = 4;
/// Batches timed between two read-backs.
const BATCHES: u32 = 1024;

/// A ring of timestamp queries, read back when full and at the end.
pub struct PassTimers {
    set: wgpu::QuerySet,
    resolved: wgpu::Buffer,
    next: u32,
    /// Nanoseconds per timestamp tick.
    period_ns: f64,
    /// What was read back so far.
    pub seconds: GpuPassSeconds,
}

impl PassTimers {
    /// Timers on `gpu`, or `None` where the device has no timestamp queries.
    pub fn new(gpu: &Gpu) -> Option<PassTimers> {
        if !gpu
            .device
            .features()
            .contains(wgpu::Features::TIMESTAMP_QUERY)
        {
            return None;
        }
        let count = PER_BATCH * BATCHES;
        let set = gpu.device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("radiosity pass timers"),
            ty: wgpu::QueryType::Timestamp,
            count,
        });
        let resolved = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("radiosity pass timestamps"),
            size: 8 * u64::from(count),
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        Some(PassTimers {
            set,
            resolved,
            next: 0,
            period_ns: f64::from(gpu.queue.get_timestamp_period()),
            seconds: GpuPassSeconds::default(),
        })
    }

    /// The next batch's queries (map pass, receive pass), reading back the ring first
    /// when it is full.
    pub fn next_batch(&mut self, gpu: &Gpu) -> Result<BatchQueries<'_>, GpuError> {
        if self.next + PER_BATCH > PER_BATCH * BATCHES {
            self.read_back(gpu)?;
        }
        let first = self.next;
        self.next += PER_BATCH;
        Ok(BatchQueries {
            set: &self.set,
            first,
        })
    }

    /// Reads the timestamps written so far and adds them to [`PassTimers::seconds`].
    pub fn read_back(&mut self, gpu: &Gpu) -> Result<(), GpuError> {
        if self.next == 0 {
            return Ok(());
        }
        let count = self.next;
        let bytes = gpu.read_bytes_prefix(&self.resolved, 8 * u64::from(count), |enc| {
            enc.resolve_query_set(&self.set, 0..count, &self.resolved, 0);
        })?;
        let ticks: Vec<u64> = bytemuck::pod_collect_to_vec(&bytes);
        let span = |a: u64, b: u64| b.saturating_sub(a) as f64 * self.period_ns * 1e-9;
        for batch in ticks.chunks_exact(PER_BATCH as usize) {
            self.seconds.maps += span(batch[0], batch[1]);
            self.seconds.receive += span(batch[2], batch[3]);
            self.seconds.batches += 1;
        }
        self.next = 0;
        Ok(())
    }
}

/// One batch's four queries.
pub struct BatchQueries<'a> {
    set: &'a wgpu::QuerySet,
    first: u32,
}

impl<'a> BatchQueries<'a> {
    /// The visibility render pass's timestamp writes.
    pub fn maps(&self) -> wgpu::RenderPassTimestampWrites<'a> {
        wgpu::RenderPassTimestampWrites {
            query_set: self.set,
            beginning_of_pass_write_index: Some(self.first),
            end_of_pass_write_index: Some(self.first + 1),
        }
    }

    /// The visibility pass's timestamp writes where the maps are drawn by compute
    /// shaders ([`super::Raster::Compute`]).
    pub fn maps_compute(&self) -> wgpu::ComputePassTimestampWrites<'a> {
        wgpu::ComputePassTimestampWrites {
            query_set: self.set,
            beginning_of_pass_write_index: Some(self.first),
            end_of_pass_write_index: Some(self.first + 1),
        }
    }

    /// The receive compute pass's timestamp writes.
    pub fn receive(&self) -> wgpu::ComputePassTimestampWrites<'a> {
        wgpu::ComputePassTimestampWrites {
            query_set: self.set,
            beginning_of_pass_write_index: Some(self.first + 2),
            end_of_pass_write_index: Some(self.first + 3),
        }
    }
}
