//! The checks of the paths a command writes, made before anything runs.

use crate::error::ConfigError;

/// Checks that the file `path` that flag `flag` names can be written, so that a path where
/// nothing can be written is refused before a run, not after it. Leaves no file behind (an
/// existing one is opened for appending, and kept as it was).
pub fn check_writable_file(flag: &'static str, path: &std::path::Path) -> Result<(), ConfigError> {
    let existed = path.exists();
    std::fs::OpenOptions::new()
        .append(true)
        .create(true)
        .open(path)
        .map_err(|err| ConfigError::OutputPath {
            flag,
            path: path.to_owned(),
            reason: err.to_string(),
        })?;
    if !existed {
        std::fs::remove_file(path).ok();
    }
    Ok(())
}

/// Creates the folder `path` that flag `flag` names (and its parents), and checks that a
/// file can be written in it.
pub fn writable_dir(flag: &'static str, path: &std::path::Path) -> Result<(), ConfigError> {
    let refuse = |err: std::io::Error| ConfigError::OutputPath {
        flag,
        path: path.to_owned(),
        reason: err.to_string(),
    };
    std::fs::create_dir_all(path).map_err(refuse)?;
    let probe = path.join(".rope-write-check");
    std::fs::write(&probe, b"").map_err(refuse)?;
    std::fs::remove_file(&probe).map_err(refuse)
}
