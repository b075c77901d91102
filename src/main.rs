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
    let cli = goniolight::cli::Cli::parse();
    match goniolight::cli::run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {}", e.message());
            ExitCode::from(e.code())
        }
    }
}
