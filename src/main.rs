use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    let cli = goniolight::cli::Cli::parse();
    match goniolight::cli::run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {:#}", e.error);
            ExitCode::from(e.code())
        }
    }
}
