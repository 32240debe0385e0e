//! The checks of the paths a command writes, made before anything runs.

use crate::error::ConfigError;

/// Checks that the file `path` that flag `flag` names can be written, so that a path where
/// nothing can be written is refused before a run, not after it. Nothing appears at `path`:
/// an existing file is opened for appending and kept as it was; for a new one, a file beside
/// it is written and removed (a script waiting for `path` to appear sees only the real one).
pub fn check_writable_file(flag: &'static str, path: &std::path::Path) -> Result<(), ConfigError> {
    let refuse = |err: std::io::Error| ConfigError::OutputPath {
        flag,
        path: path.to_owned(),
        reason: err.to_string(),
    };
    if path.exists() {
        std::fs::OpenOptions::new()
            .append(true)
            .open(path)
            .map_err(refuse)?;
        return Ok(());
    }
    if path
        .as_os_str()
        .to_string_lossy()
        .ends_with(std::path::MAIN_SEPARATOR)
    {
        return Err(refuse(std::io::ErrorKind::IsADirectory.into()));
    }
    let probe = beside(path, "rope-write-check");
    std::fs::write(&probe, b"").map_err(refuse)?;
    std::fs::remove_file(&probe).map_err(refuse)
}

/// Writes `contents` to `path` whole: into a file beside it, then renamed over it, so that a
/// reader never finds it half written.
pub fn write_whole(path: &std::path::Path, contents: &[u8]) -> std::io::Result<()> {
    let partial = beside(path, "partial");
    std::fs::write(&partial, contents)?;
    std::fs::rename(&partial, path).inspect_err(|_| {
        std::fs::remove_file(&partial).ok();
    })
}

/// A hidden file in `path`'s folder named after it: `.NAME.suffix`.
fn beside(path: &std::path::Path, suffix: &str) -> std::path::PathBuf {
    let name = path.file_name().unwrap_or_default().to_string_lossy();
    path.with_file_name(format!(".{name}.{suffix}"))
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
