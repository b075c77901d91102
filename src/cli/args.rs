//! Checks of command-line arguments shared by several commands.

use super::error::CliError;

/// clap's parser of a number of seconds (time limits): positive, finite and at most
/// [`crate::io::limits::MAX_SECONDS`], so that no later conversion to a duration fails.
pub(crate) fn seconds_arg(s: &str) -> Result<f64, String> {
    let v: f64 = s.trim().parse().map_err(|e| format!("{s:?}: {e}"))?;
    crate::io::limits::duration(v)?;
    Ok(v)
}

/// An error naming `flag` when the folder `path` goes into does not exist (checked before
/// the work, so that the run does not fail at its end).
pub(crate) fn check_folder_of(path: &std::path::Path, flag: &str) -> Result<(), CliError> {
    let folder = path.parent().filter(|p| !p.as_os_str().is_empty());
    if folder.is_some_and(|f| !f.is_dir()) {
        return Err(CliError::input(anyhow::anyhow!(
            "{flag} {}: the folder {} does not exist",
            path.display(),
            folder.expect("checked").display()
        )));
    }
    Ok(())
}
