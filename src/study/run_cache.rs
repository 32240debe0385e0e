//! Runs kept on disk: the tip of a reference's run (up to twenty minutes of CPU at N = 12 800)
//! read back instead of run again, where the environment variable [`ENV`] names a folder. A
//! kept run is bit for bit what the run gave, so a study made with the folder is the study
//! made without it: the release atlas and the tolerance check may share their references'
//! runs, and a check stopped partway keeps the runs it finished.

use crate::methods::MethodKind;
use crate::model::{Point, Scene};
use std::io::{BufRead as _, Read as _, Write as _};
use std::path::{Path, PathBuf};

/// The environment variable that names the folder runs are kept in (unset or empty: none).
pub const ENV: &str = "ROPE_RUN_CACHE";

/// One run's place in the folder: which run it is, written at the head of its file and
/// checked when it is read back.
pub struct Kept {
    path: PathBuf,
    header: String,
}

impl Kept {
    /// Where `method`'s run from `scene` at `segments` and step `dt` to `duration` is kept;
    /// `None` where no folder is named.
    pub fn of(
        method: MethodKind,
        scene: &Scene,
        segments: usize,
        dt: f64,
        duration: f64,
    ) -> Option<Self> {
        let folder = std::env::var_os(ENV).filter(|v| !v.is_empty())?;
        Some(Self::in_folder(
            Path::new(&folder),
            method,
            scene,
            segments,
            dt,
            duration,
        ))
    }

    /// As [`Kept::of`], in `folder`.
    fn in_folder(
        folder: &Path,
        method: MethodKind,
        scene: &Scene,
        segments: usize,
        dt: f64,
        duration: f64,
    ) -> Self {
        let scene_name: String = scene
            .to_string()
            .chars()
            .map(|c| if c.is_ascii_alphanumeric() { c } else { '-' })
            .collect();
        let name = format!(
            "{method}-{scene_name}-{segments}-{:016x}-{:016x}.tips",
            dt.to_bits(),
            duration.to_bits()
        );
        let header = format!(
            "rope run tips 1: {method}, {scene:?}, N = {segments}, k = {:016x}, to t = {:016x}",
            dt.to_bits(),
            duration.to_bits()
        );
        Self {
            path: folder.join(name),
            header,
        }
    }

    /// The run as it was kept, its step and its tip at every step from t = 0; `None` if it
    /// was not, or its file is not this run's whole.
    pub fn load(&self) -> Option<(f64, Vec<Point>)> {
        let file = std::fs::File::open(&self.path).ok()?;
        let mut reader = std::io::BufReader::new(file);
        let mut header = String::new();
        reader.read_line(&mut header).ok()?;
        if header.trim_end() != self.header {
            return None;
        }
        let mut count = String::new();
        reader.read_line(&mut count).ok()?;
        let (dt, count): (u64, usize) = {
            let (dt, count) = count.trim_end().split_once(' ')?;
            (u64::from_str_radix(dt, 16).ok()?, count.parse().ok()?)
        };
        let mut bytes = Vec::new();
        reader.read_to_end(&mut bytes).ok()?;
        if bytes.len() != count * 16 {
            return None;
        }
        let number = |b: &[u8]| b.try_into().ok().map(f64::from_le_bytes);
        let tips = bytes
            .chunks_exact(16)
            .map(|p| Some(Point::new(number(&p[..8])?, number(&p[8..])?)))
            .collect::<Option<Vec<_>>>()?;
        Some((f64::from_bits(dt), tips))
    }

    /// Keeps the run of step `dt` and tips `tips` (written whole to a file of its own, then
    /// moved into place, so that a run stopped while writing leaves nothing half-written, and
    /// a write that fails leaves nothing at all).
    pub fn store(&self, dt: f64, tips: &[Point]) -> anyhow::Result<()> {
        let partial = self
            .path
            .with_extension(format!("partial-{}", std::process::id()));
        let write = || -> std::io::Result<()> {
            if let Some(folder) = self.path.parent() {
                std::fs::create_dir_all(folder)?;
            }
            let mut out = std::io::BufWriter::new(std::fs::File::create(&partial)?);
            writeln!(out, "{}", self.header)?;
            writeln!(out, "{:016x} {}", dt.to_bits(), tips.len())?;
            for tip in tips {
                out.write_all(&tip.x.to_le_bytes())?;
                out.write_all(&tip.y.to_le_bytes())?;
            }
            out.into_inner().map_err(|e| e.into_error())?.sync_all()?;
            std::fs::rename(&partial, &self.path)
        };
        write().map_err(|error| {
            // Nothing half-written is left behind; the file may never have been made.
            let _ = std::fs::remove_file(&partial);
            anyhow::Error::new(error).context(format!(
                "keeping a run in {} (the folder {ENV} names)",
                self.path.display()
            ))
        })
    }
}

/// The run `compute` makes (its step and its tip at every step), read back instead where
/// `kept` holds it, and kept there once made. A run that cannot be kept (the folder is not
/// writable, the disk is full) is not lost: it is returned all the same, and the first such
/// failure is told on stderr, once, as a warning (the runs this keeps take up to twenty
/// minutes; a study should not lose them to a folder that only saves time).
pub fn computed_or_kept(
    kept: Option<Kept>,
    compute: impl FnOnce() -> anyhow::Result<(f64, Vec<Point>)>,
) -> anyhow::Result<(f64, Vec<Point>)> {
    if let Some(run) = kept.as_ref().and_then(Kept::load) {
        return Ok(run);
    }
    let (dt, tips) = compute()?;
    if let Some(Err(error)) = kept.map(|kept| kept.store(dt, &tips)) {
        static TOLD: std::sync::Once = std::sync::Once::new();
        TOLD.call_once(|| {
            eprintln!("rope: warning: {error:#}; the runs go on without being kept");
        });
    }
    Ok((dt, tips))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_kept_run_reads_back_bit_for_bit_and_only_as_itself() {
        let folder = std::env::temp_dir().join(format!("rope-run-cache-{}", std::process::id()));
        let scene = Scene::Release { angle_deg: 30.0 };
        let (method, dt) = (MethodKind::Chain, 1e-3);
        let tips: Vec<Point> = (0..100)
            .map(|i| Point::new((i as f64 * 0.1).sin(), 1.0 / (i as f64 + 3.0)))
            .collect();
        let kept = Kept::in_folder(&folder, method, &scene, 16, dt, 3.0);
        assert!(kept.load().is_none());
        kept.store(dt, &tips).unwrap();
        assert_eq!(kept.load(), Some((dt, tips)));
        // Another run's place does not read it: another N, step, duration or scene.
        let other = |n, dt, duration, angle_deg| {
            let scene = Scene::Release { angle_deg };
            Kept::in_folder(&folder, method, &scene, n, dt, duration).load()
        };
        assert!(other(32, dt, 3.0, 30.0).is_none());
        assert!(other(16, dt * (1.0 + f64::EPSILON), 3.0, 30.0).is_none());
        assert!(other(16, dt, 3.5, 30.0).is_none());
        assert!(other(16, dt, 3.0, 31.0).is_none());
        // A file cut short is not read.
        let bytes = std::fs::read(&kept.path).unwrap();
        std::fs::write(&kept.path, &bytes[..bytes.len() - 8]).unwrap();
        assert!(kept.load().is_none());
        std::fs::remove_dir_all(&folder).unwrap();
    }

    #[test]
    fn a_run_that_cannot_be_kept_is_returned_and_leaves_no_partial_file() {
        let root = std::env::temp_dir().join(format!("rope-run-unkept-{}", std::process::id()));
        std::fs::create_dir_all(&root).unwrap();
        // The folder to keep runs in is a file: nothing can be written under it.
        let blocker = root.join("not-a-folder");
        std::fs::write(&blocker, b"a file").unwrap();
        let scene = Scene::Release { angle_deg: 30.0 };
        let kept = Kept::in_folder(&blocker, MethodKind::Chain, &scene, 16, 1e-3, 3.0);
        let tips = vec![Point::new(0.5, -0.5), Point::new(0.25, -0.75)];
        let stored = kept.store(1e-3, &tips);
        assert!(stored.is_err(), "a file cannot hold a folder");
        let run = computed_or_kept(Some(kept), || Ok((1e-3, tips.clone()))).unwrap();
        assert_eq!(run, (1e-3, tips));
        let left: Vec<_> = std::fs::read_dir(&root).unwrap().flatten().collect();
        assert_eq!(left.len(), 1, "only the blocking file is left: {left:?}");
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn a_write_that_fails_midway_leaves_no_partial_file() {
        let folder = std::env::temp_dir().join(format!("rope-run-midway-{}", std::process::id()));
        std::fs::create_dir_all(&folder).unwrap();
        let scene = Scene::Release { angle_deg: 30.0 };
        let kept = Kept::in_folder(&folder, MethodKind::Chain, &scene, 16, 1e-3, 3.0);
        // The place the run would be moved to is a folder that is not empty: the rename fails
        // after the partial file was written whole.
        std::fs::create_dir_all(kept.path.join("occupied")).unwrap();
        assert!(kept.store(1e-3, &[Point::new(0.5, -0.5)]).is_err());
        let left: Vec<_> = std::fs::read_dir(&folder).unwrap().flatten().collect();
        assert_eq!(left.len(), 1, "only the occupying folder is left: {left:?}");
        std::fs::remove_dir_all(&folder).unwrap();
    }
}
