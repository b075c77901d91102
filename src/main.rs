use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    // Behave like other Unix filters when the reader of our output goes away
    // (`goniolight … | head`): end quietly instead of panicking on a broken pipe.
    #[cfg(unix)]
    // SAFETY: restoring the default disposition of SIGPIPE before any thread starts.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    // Without XDG_RUNTIME_DIR, libwayland (probed by the GPU drivers even for headless
    // work) prints "XDG_RUNTIME_DIR is invalid or not set" twice on every GPU command.
    // Pointing it at the temporary folder, where no Wayland socket is, keeps it quiet;
    // a real Wayland session sets the variable and is left alone.
    if std::env::var_os("XDG_RUNTIME_DIR").is_none()
        && std::env::var_os("WAYLAND_DISPLAY").is_none()
    {
        // SAFETY: no other thread exists yet.
        unsafe { std::env::set_var("XDG_RUNTIME_DIR", std::env::temp_dir()) };
    }
    let cli = goniolight::cli::Cli::parse();
    match goniolight::cli::run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {}", e.message());
            ExitCode::from(e.code())
        }
    }
}
