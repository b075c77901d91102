//! The process-wide interrupt flag: SIGINT (Ctrl-C), SIGTERM and SIGHUP end every command
//! cleanly; a long command polls the flag and stops between steps.

/// Whether the running command polls [`interrupt_flag`] (it asked for it): then a first
/// signal lets it finish its step; otherwise a signal ends the process at once.
static POLLED: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// The process-wide flag set by SIGINT (Ctrl-C), SIGTERM or SIGHUP. A command that calls
/// this polls it: the first signal sets it, and the command finishes its current step and
/// writes a complete set or nothing (as each documents), a batch starts no further job. A
/// second signal, or the first in a command that never asked for the flag, removes the
/// temporary files and staging folders of the writes in progress and ends the process at
/// once (exit 130).
pub fn interrupt_flag() -> std::sync::Arc<std::sync::atomic::AtomicBool> {
    POLLED.store(true, std::sync::atomic::Ordering::SeqCst);
    signal_flag()
}

/// The flag, with the handler installed on first use.
pub(super) fn signal_flag() -> std::sync::Arc<std::sync::atomic::AtomicBool> {
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::sync::{Arc, OnceLock};
    static FLAG: OnceLock<Arc<AtomicBool>> = OnceLock::new();
    FLAG.get_or_init(|| {
        let flag = Arc::new(AtomicBool::new(false));
        let set = flag.clone();
        let _ = ctrlc::set_handler(move || {
            if !POLLED.load(Ordering::SeqCst) || set.swap(true, Ordering::SeqCst) {
                // Nothing half-written stays: the temporary files and staging folders go.
                crate::io::outputs::remove_unfinished();
                std::process::exit(130);
            }
            eprintln!("\ninterrupted: finishing the current step (Ctrl-C again to quit)");
        });
        flag
    })
    .clone()
}
