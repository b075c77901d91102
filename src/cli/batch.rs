//! `goniolight batch JOBS.toml`: a list of independent command lines run in one process
//! (one GPU start-up for all), with a progress bar, a JSON summary and `--shard K/N` so
//! that one jobs file splits across machines (GNU parallel, a Slurm job array).
//!
//! The jobs file:
//! ```toml
//! [[job]]
//! name = "office"                                  # optional (default "job-N", 1-based)
//! args = ["render", "scenes/office.toml", "--out", "out/office.png"]
//! stdout = "out/office.txt"                        # optional: the job's standard output
//! stdin = "points/office.txt"                      # optional: its standard input
//! ```
//! Relative paths (in `args`, `stdout`, `stdin`) are relative to the jobs file's folder.
//! Job i (0-based, in file order) belongs to shard K of N when i mod N = K − 1, so the
//! shards of one file together run every job exactly once, each writing the same files as
//! an unsharded run. A job's standard output without `stdout` goes to standard error, so
//! the batch's own standard output is its summary.

use std::path::{Path, PathBuf};
use std::sync::atomic::Ordering;
use std::time::Instant;

use anyhow::anyhow;
use clap::Args;
use serde::{Deserialize, Serialize};

use super::error::CliError;
use super::interrupt::interrupt_flag;

/// Runs one job's command line (without the program's name).
pub type RunLine<'a> = &'a dyn Fn(&[String]) -> Result<(), CliError>;

/// Options of `batch`.
#[derive(Debug, Args)]
pub struct BatchArgs {
    /// The jobs file (TOML, `[[job]]` tables with `args`, optional `name`, `stdout`, `stdin`).
    pub jobs: PathBuf,
    /// Run only shard K of N (1-based): the jobs whose 0-based index i has i mod N = K − 1.
    #[arg(long, value_name = "K/N")]
    pub shard: Option<String>,
    /// Write the JSON summary here instead of standard output.
    #[arg(long)]
    pub summary: Option<PathBuf>,
    /// Stop at the first failed job (default: run the others and exit 1 at the end).
    #[arg(long)]
    pub fail_fast: bool,
}

/// The jobs file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct JobsFile {
    #[serde(default)]
    job: Vec<Job>,
}

/// One job of the file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct Job {
    name: Option<String>,
    args: Vec<String>,
    stdout: Option<PathBuf>,
    stdin: Option<PathBuf>,
}

/// A job's outcome, as the summary reports it.
#[derive(Debug, Serialize)]
struct JobResult {
    index: usize,
    name: String,
    args: Vec<String>,
    exit_code: u8,
    error: Option<String>,
    seconds: f64,
}

/// The summary of a batch run.
#[derive(Debug, Serialize)]
struct Summary {
    jobs_file: String,
    shard: [usize; 2],
    total_jobs: usize,
    ran: usize,
    failed: usize,
    interrupted: bool,
    seconds: f64,
    jobs: Vec<JobResult>,
}

/// Parses `K/N` (1 ≤ K ≤ N).
fn parse_shard(s: &str) -> Result<[usize; 2], CliError> {
    let bad = || {
        CliError::input(anyhow!(
            "--shard {s:?}: expected K/N with 1 ≤ K ≤ N, e.g. 2/8"
        ))
    };
    let (k, n) = s.split_once('/').ok_or_else(bad)?;
    let k: usize = k.trim().parse().map_err(|_| bad())?;
    let n: usize = n.trim().parse().map_err(|_| bad())?;
    if k == 0 || n == 0 || k > n {
        return Err(bad());
    }
    Ok([k, n])
}

/// Reads and checks the jobs file (at most [`crate::io::MAX_TEXT_BYTES`], no device).
fn read_jobs(path: &Path) -> Result<Vec<Job>, CliError> {
    let text = crate::io::read_text_limited(path, crate::io::MAX_TEXT_BYTES)
        .map_err(|e| CliError::input(anyhow!("{}: {e}", path.display())))?;
    parse_jobs(path, &text)
}

/// The number of jobs in a jobs file's text, or the error `batch` gives for it (`path`
/// names it in messages): for fuzzing and editors.
pub fn count_jobs(path: &Path, text: &str) -> Result<usize, CliError> {
    parse_jobs(path, text).map(|jobs| jobs.len())
}

/// Parses and checks a jobs file's text.
fn parse_jobs(path: &Path, text: &str) -> Result<Vec<Job>, CliError> {
    let file: JobsFile =
        toml::from_str(text).map_err(|e| CliError::input(anyhow!("{}: {e}", path.display())))?;
    if file.job.is_empty() {
        return Err(CliError::input(anyhow!(
            "{}: no [[job]] tables (each needs args = [\"command\", …])",
            path.display()
        )));
    }
    for (i, job) in file.job.iter().enumerate() {
        let first = job.args.first().map(String::as_str);
        let why = match first {
            None => Some("args is empty"),
            Some("batch") => Some("a batch cannot run a batch"),
            Some("view") => Some("view is interactive and cannot run in a batch"),
            _ => None,
        };
        if let Some(why) = why {
            return Err(CliError::input(anyhow!(
                "{}: job[{i}].args: {why}",
                path.display()
            )));
        }
    }
    Ok(file.job)
}

/// Refuses (before any job runs) a job `stdout` or the `--summary` that is the jobs file,
/// a job's stdin or any existing file a job's arguments name, that is another job's
/// `stdout`, or that is no regular file; and a job `stdin` that is a device.
fn check_outputs(args: &BatchArgs, jobs: &[Job]) -> Result<(), CliError> {
    let base = args.jobs.parent().unwrap_or(Path::new(""));
    let mut check = crate::io::outputs::OutputCheck::new();
    check.input(&args.jobs);
    for (i, job) in jobs.iter().enumerate() {
        if let Some(p) = &job.stdin {
            let p = base.join(p);
            if let Ok(meta) = std::fs::metadata(&p) {
                if !meta.is_file() {
                    return Err(CliError::input(anyhow!(
                        "{}: job[{i}].stdin {}: not a regular file (a device or FIFO never ends)",
                        args.jobs.display(),
                        p.display()
                    )));
                }
            }
            check.input(p);
        }
        for a in &job.args {
            let p = base.join(a);
            if p.is_file() {
                check.input(p);
            }
        }
    }
    for (i, job) in jobs.iter().enumerate() {
        if let Some(p) = &job.stdout {
            check.named_output(&format!("job[{i}].stdout {}", p.display()), base.join(p));
        }
    }
    if let Some(p) = &args.summary {
        check.named_output(&format!("--summary {}", p.display()), p);
    }
    check
        .check()
        .map_err(|e| CliError::input(anyhow!("{}: {e}", args.jobs.display())))
}

/// Runs `batch`.
pub fn run(args: BatchArgs, run_line: RunLine<'_>) -> Result<(), CliError> {
    let shard = match &args.shard {
        Some(s) => parse_shard(s)?,
        None => [1, 1],
    };
    let jobs = read_jobs(&args.jobs)?;
    check_outputs(&args, &jobs)?;
    // Resolve our own paths before moving into the jobs file's folder.
    let summary_path = args
        .summary
        .as_ref()
        .map(|p| std::path::absolute(p).unwrap_or_else(|_| p.clone()));
    let base = args
        .jobs
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
        .to_path_buf();
    let cwd = std::env::current_dir().map_err(CliError::failure)?;
    std::env::set_current_dir(&base)
        .map_err(|e| CliError::input(anyhow!("{}: {e}", base.display())))?;
    let result = run_jobs(&args, &jobs, shard, run_line);
    std::env::set_current_dir(&cwd).map_err(CliError::failure)?;
    let summary = result?;
    let json = serde_json::to_string_pretty(&summary).map_err(CliError::failure)?;
    match summary_path {
        Some(p) => crate::io::write_atomic(&p, format!("{json}\n").as_bytes())
            .map_err(CliError::failure)?,
        None => println!("{json}"),
    }
    if summary.interrupted {
        return Err(CliError::failure(anyhow!(
            "interrupted after {} of the shard's jobs",
            summary.ran
        )));
    }
    if summary.failed > 0 {
        return Err(CliError::failure(anyhow!(
            "{} of {} jobs failed (see the summary)",
            summary.failed,
            summary.ran
        )));
    }
    Ok(())
}

fn run_jobs(
    args: &BatchArgs,
    jobs: &[Job],
    shard: [usize; 2],
    run_line: RunLine<'_>,
) -> Result<Summary, CliError> {
    let start = Instant::now();
    let mine: Vec<(usize, &Job)> = jobs
        .iter()
        .enumerate()
        .filter(|(i, _)| i % shard[1] == shard[0] - 1)
        .collect();
    let bar = indicatif::ProgressBar::new(mine.len() as u64);
    if let Ok(style) = indicatif::ProgressStyle::with_template("{bar:30} {pos}/{len} jobs {msg}") {
        bar.set_style(style);
    }
    let interrupt = interrupt_flag();
    let mut results = Vec::new();
    let mut interrupted = false;
    for (index, job) in mine {
        if interrupt.load(Ordering::SeqCst) {
            interrupted = true;
            break;
        }
        let name = job.name.clone().unwrap_or(format!("job-{}", index + 1));
        bar.set_message(name.clone());
        let t = Instant::now();
        let outcome = run_job(job, run_line);
        let failed = outcome.is_err();
        results.push(JobResult {
            index,
            name,
            args: job.args.clone(),
            exit_code: outcome.as_ref().map_or_else(CliError::code, |_| 0),
            error: outcome.err().map(|e| e.message()),
            seconds: t.elapsed().as_secs_f64(),
        });
        bar.inc(1);
        if failed && args.fail_fast {
            break;
        }
    }
    bar.finish_and_clear();
    let failed = results.iter().filter(|r| r.exit_code != 0).count();
    Ok(Summary {
        jobs_file: args.jobs.display().to_string(),
        shard,
        total_jobs: jobs.len(),
        ran: results.len(),
        failed,
        interrupted,
        seconds: start.elapsed().as_secs_f64(),
        jobs: results,
    })
}

/// Runs one job with its standard input and output redirected.
fn run_job(job: &Job, run_line: RunLine<'_>) -> Result<(), CliError> {
    let _stdin = match &job.stdin {
        Some(p) => {
            let file = std::fs::File::open(p)
                .map_err(|e| CliError::input(anyhow!("stdin {}: {e}", p.display())))?;
            Some(redirect::Redirect::new(0, &file).map_err(CliError::failure)?)
        }
        None => None,
    };
    match &job.stdout {
        None => {
            let _out = redirect::Redirect::to_stderr().map_err(CliError::failure)?;
            run_line(&job.args)
        }
        Some(p) => {
            let tmp = crate::io::outputs::temporary_beside(p, "tmp")
                .map_err(|e| CliError::input(anyhow!("stdout {}: {e}", p.display())))?;
            if let Some(dir) = p.parent().filter(|d| !d.as_os_str().is_empty()) {
                std::fs::create_dir_all(dir)
                    .map_err(|e| CliError::failure(anyhow!("stdout {}: {e}", p.display())))?;
            }
            let file = std::fs::File::create(&tmp)
                .map_err(|e| CliError::failure(anyhow!("stdout {}: {e}", p.display())))?;
            let result = {
                let _out = redirect::Redirect::new(1, &file).map_err(CliError::failure)?;
                run_line(&job.args)
            };
            let done = result.and_then(|()| {
                file.sync_all()
                    .and_then(|()| std::fs::rename(&tmp, p))
                    .map_err(|e| CliError::failure(anyhow!("stdout {}: {e}", p.display())))
            });
            if done.is_err() {
                let _ = std::fs::remove_file(&tmp);
            }
            crate::io::outputs::finished(&tmp);
            done
        }
    }
}

/// Standard input/output redirected for the duration of a job (file descriptors, so the
/// commands' own `println!` and `stdin()` follow).
mod redirect {
    use std::io::Write;
    use std::os::fd::AsRawFd;

    /// Points `fd` elsewhere until dropped.
    pub struct Redirect {
        fd: i32,
        saved: i32,
    }

    impl Redirect {
        /// Points `fd` (0 or 1) at `file`.
        pub fn new(fd: i32, file: &std::fs::File) -> std::io::Result<Redirect> {
            Redirect::to_fd(fd, file.as_raw_fd())
        }

        /// Points standard output at standard error.
        pub fn to_stderr() -> std::io::Result<Redirect> {
            Redirect::to_fd(1, 2)
        }

        fn to_fd(fd: i32, target: i32) -> std::io::Result<Redirect> {
            let _ = std::io::stdout().flush();
            // SAFETY: plain descriptor calls on descriptors this process owns.
            let saved = unsafe { libc::dup(fd) };
            if saved < 0 {
                return Err(std::io::Error::last_os_error());
            }
            // SAFETY: as above.
            if unsafe { libc::dup2(target, fd) } < 0 {
                let e = std::io::Error::last_os_error();
                // SAFETY: closing the copy made above.
                unsafe { libc::close(saved) };
                return Err(e);
            }
            Ok(Redirect { fd, saved })
        }
    }

    impl Drop for Redirect {
        fn drop(&mut self) {
            let _ = std::io::stdout().flush();
            // SAFETY: restoring the descriptor saved in `to_fd` and closing the copy.
            unsafe {
                libc::dup2(self.saved, self.fd);
                libc::close(self.saved);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_are_parsed_and_checked() {
        assert_eq!(parse_shard("2/8").unwrap(), [2, 8]);
        assert_eq!(parse_shard("1/1").unwrap(), [1, 1]);
        for bad in ["0/2", "3/2", "1", "a/b", "1/0"] {
            assert!(parse_shard(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn bad_jobs_files_name_the_job() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("jobs.toml");
        for (text, wanted) in [
            ("[[job]]\nargs = []\n", "job[0].args: args is empty"),
            (
                "[[job]]\nargs = [\"sun\"]\n[[job]]\nargs = [\"view\"]\n",
                "job[1].args",
            ),
            ("[[job]]\nargz = [\"sun\"]\n", "unknown field"),
            ("", "no [[job]] tables"),
        ] {
            std::fs::write(&p, text).unwrap();
            let e = read_jobs(&p).unwrap_err();
            let msg = e.message();
            assert!(e.bad_input && msg.contains(wanted), "{msg}");
        }
    }
}
