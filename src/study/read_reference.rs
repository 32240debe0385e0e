//! A reference read back from a file in the columns of `references.csv` (what
//! `rope study --tolerance-check` and `examples/reference_convergence` write): a scene's
//! converged tip and its own error at each row, for the check to judge runs against instead of
//! computing the reference again (`--references`). It is read at its rows, never between
//! them, so every frame must be a row; and [`CheckReference`], a scene's reference in the
//! check, read or computed.

use super::tip_reference::{
    ConvergedTip, JUDGE_RATE, LOG_RATE, REFERENCE_RATE, REFERENCE_ROWS_RATE,
    REFERENCES_HEADER as HEADER, TipReference, csv_field,
};
use crate::error::ConfigError;
use crate::model::{Point, Scene};
use std::path::{Path, PathBuf};

/// One scene's converged tip read from a references file.
#[derive(Clone, Debug)]
pub struct ReadReference {
    pub scene: Scene,
    /// The file it was read from.
    pub source: PathBuf,
    /// Rows a time unit: row k is at t = k / rate.
    pub rate: f64,
    /// The tip and its own error at each row.
    rows: Vec<(Point, f64)>,
    /// The largest own error at every row (1/[`JUDGE_RATE`] of a time unit) to the duration
    /// read for.
    pub own_error: f64,
}

impl ReadReference {
    /// The row nearest time `t` (the last row past the file's end).
    fn row(&self, t: f64) -> &(Point, f64) {
        let k = (t * self.rate).round().max(0.0) as usize;
        &self.rows[k.min(self.rows.len() - 1)]
    }
}

impl ConvergedTip for ReadReference {
    fn scene(&self) -> Scene {
        self.scene
    }

    /// The tip of the row nearest `t`: a frame, or any 1/[`REFERENCE_ROWS_RATE`], is a row.
    fn tip_at(&self, t: f64) -> Point {
        self.row(t).0
    }

    fn own_error_at(&self, t: f64) -> f64 {
        self.row(t).1
    }

    fn rows_only(&self) -> bool {
        true
    }
}

/// Every reference that `paths` hold of one of `scenes`, each checked to serve a check to
/// `duration`: a row at every 1/[`REFERENCE_ROWS_RATE`] (every frame and every
/// 1/[`REFERENCE_RATE`]) from t = 0 to `duration` at least. A path is a references file, or a
/// folder whose `.csv` files that begin with [`HEADER`] are read (others, such as a
/// `levels.csv` beside them, are passed over). Rows of scenes not in `scenes` are left out.
pub fn read_all(
    paths: &[PathBuf],
    scenes: &[Scene],
    duration: f64,
) -> Result<Vec<ReadReference>, ConfigError> {
    let mut read = Vec::new();
    for path in paths {
        if path.is_dir() {
            let entries = std::fs::read_dir(path).map_err(|e| unreadable(path, e.to_string()))?;
            let mut files: Vec<PathBuf> = entries
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|x| x == "csv"))
                .collect();
            files.sort();
            for file in files {
                let text = read_text(&file)?;
                if text.lines().next() == Some(HEADER) {
                    read.extend(parse(&file, &text, scenes, duration)?);
                }
            }
        } else {
            read.extend(parse(path, &read_text(path)?, scenes, duration)?);
        }
    }
    Ok(read)
}

/// Why the references file or folder at `path` cannot serve.
fn unreadable(path: &Path, reason: String) -> ConfigError {
    ConfigError::ReferencesUnreadable {
        path: path.display().to_string(),
        reason,
    }
}

fn read_text(path: &Path) -> Result<String, ConfigError> {
    std::fs::read_to_string(path).map_err(|e| unreadable(path, e.to_string()))
}

/// The references of `scenes` in the text of the file at `path`.
fn parse(
    path: &Path,
    text: &str,
    scenes: &[Scene],
    duration: f64,
) -> Result<Vec<ReadReference>, ConfigError> {
    let mut lines = text.lines().enumerate();
    match lines.next() {
        Some((_, HEADER)) => {}
        first => {
            return Err(unreadable(
                path,
                format!(
                    "its first line is {:?}, not the header of a references file, {HEADER:?}",
                    first.map_or("", |(_, l)| l)
                ),
            ));
        }
    }
    let labels: Vec<String> = scenes.iter().map(|s| csv_field(&s.to_string())).collect();
    let mut rows: Vec<Vec<(f64, Point, f64)>> = vec![Vec::new(); scenes.len()];
    for (i, line) in lines {
        // The label first (quoted where it holds a comma), then four numbers.
        let mut fields: Vec<&str> = line.rsplitn(5, ',').collect();
        fields.reverse();
        let bad = |what: &str| unreadable(path, format!("line {}: {what}: {line:?}", i + 1));
        let [label, t, x, y, own] = fields[..] else {
            return Err(bad("not five fields"));
        };
        let Some(s) = labels.iter().position(|l| l == label) else {
            continue;
        };
        let number = |field: &str| field.parse::<f64>().ok().filter(|v| v.is_finite());
        let (Some(t), Some(x), Some(y), Some(own)) = (number(t), number(x), number(y), number(own))
        else {
            return Err(bad("a field that is not a finite number"));
        };
        rows[s].push((t, Point::new(x, y), own));
    }
    scenes
        .iter()
        .zip(rows)
        .filter(|(_, rows)| !rows.is_empty())
        .map(|(scene, rows)| {
            checked(path, *scene, &rows, duration).map_err(|reason| unreadable(path, reason))
        })
        .collect()
}

/// The reference of `scene` from its `rows` (t, tip, own error), if they are a row at every
/// 1/[`REFERENCE_ROWS_RATE`] or finer, evenly, from t = 0 to `duration`; else why not.
fn checked(
    path: &Path,
    scene: Scene,
    rows: &[(f64, Point, f64)],
    duration: f64,
) -> Result<ReadReference, String> {
    let need = format!(
        "a reference needs a row at every 1/{REFERENCE_ROWS_RATE} of a time unit (every frame, \
         {LOG_RATE} a unit, and every 1/{REFERENCE_RATE}) from t = 0 to t = {duration}, as \
         `rope study --tolerance-check` writes references.csv"
    );
    let spacing = match rows {
        [(t0, ..), (t1, ..), ..] if *t0 == 0.0 && t1 > t0 => t1 - t0,
        _ => {
            return Err(format!(
                "the {scene}'s rows do not start at t = 0 and go on; {need}"
            ));
        }
    };
    let rate = (1.0 / spacing).round();
    let per_row = rate / REFERENCE_ROWS_RATE;
    if per_row < 1.0 || (per_row - per_row.round()).abs() > 1e-9 {
        return Err(format!(
            "the {scene}'s rows are 1/{rate} of a time unit apart; {need}"
        ));
    }
    if let Some((k, (t, ..))) = rows
        .iter()
        .enumerate()
        .find(|(k, (t, ..))| (t - *k as f64 / rate).abs() > 1e-9)
    {
        return Err(format!(
            "the {scene}'s row {k} is at t = {t}, not at {k}/{rate}; {need}"
        ));
    }
    let last = rows.last().map_or(0.0, |r| r.0);
    if last < duration - 1e-9 {
        return Err(format!("the {scene}'s rows end at t = {last}; {need}"));
    }
    let mut reference = ReadReference {
        scene,
        source: path.to_owned(),
        rate,
        rows: rows.iter().map(|&(_, tip, own)| (tip, own)).collect(),
        own_error: 0.0,
    };
    reference.own_error = reference.own_error_over(duration, JUDGE_RATE);
    Ok(reference)
}

/// A scene's reference in the tolerance check: read from a file, or computed from runs.
#[derive(Clone, Debug)]
pub enum CheckReference {
    Read(ReadReference),
    Computed(TipReference),
}

impl CheckReference {
    /// Its largest own error at every row.
    pub fn own_error(&self) -> f64 {
        match self {
            Self::Read(r) => r.own_error,
            Self::Computed(r) => r.own_error,
        }
    }

    /// What it is made of, as the check's table says: its method, N (runs at N/2, N and 2N)
    /// and the order they show; or the file it was read from.
    pub fn made_of(&self) -> (String, String, String) {
        match self {
            Self::Read(r) => (
                format!("read from `{}`", r.source.display()),
                "–".into(),
                "–".into(),
            ),
            Self::Computed(r) => (
                r.method.to_string(),
                r.segments.to_string(),
                format!("{:.2}", r.order),
            ),
        }
    }
}

impl ConvergedTip for CheckReference {
    fn scene(&self) -> Scene {
        match self {
            Self::Read(r) => r.scene,
            Self::Computed(r) => r.scene,
        }
    }

    fn tip_at(&self, t: f64) -> Point {
        match self {
            Self::Read(r) => r.tip_at(t),
            Self::Computed(r) => r.at(t),
        }
    }

    fn own_error_at(&self, t: f64) -> f64 {
        match self {
            Self::Read(r) => r.own_error_at(t),
            Self::Computed(r) => r.own_error_at(t),
        }
    }

    fn rows_only(&self) -> bool {
        matches!(self, Self::Read(_))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const THIRTY: Scene = Scene::Release { angle_deg: 30.0 };
    const MODE: Scene = Scene::Mode {
        number: 1,
        amplitude: 0.05,
    };

    /// A references file of `scene`'s tip on a circle, `rate` rows a unit to `until`.
    fn file(name: &str, scene: Scene, rate: f64, until: f64) -> PathBuf {
        let path = std::env::temp_dir().join(format!("rope-read-{}-{name}", std::process::id()));
        let rows = (0..=(until * rate).round() as usize).map(|k| {
            let t = k as f64 / rate;
            (scene, t, Point::new(t.cos(), t.sin()), 1e-6 * t)
        });
        super::super::tip_reference::write_reference_csv(&path, rows).unwrap();
        path
    }

    #[test]
    fn a_reference_read_back_gives_each_frame_its_row() {
        let path = file("ok.csv", THIRTY, 3000.0, 3.0);
        let read = read_all(std::slice::from_ref(&path), &[MODE, THIRTY], 3.0).unwrap();
        std::fs::remove_file(&path).unwrap();
        assert_eq!(read.len(), 1);
        let r = &read[0];
        assert_eq!((r.scene, r.rate), (THIRTY, 3000.0));
        for t in [0.0, 1.0 / 60.0, 1.234, 2.5, 3.0] {
            assert!(
                (r.tip_at(t) - Point::new(t.cos(), t.sin())).norm() < 1e-8,
                "t = {t}"
            );
        }
        // Own errors are printed to two digits: 3e-6 at t = 3.
        assert!((r.own_error - 3e-6).abs() < 1e-12, "{}", r.own_error);
        // A scene the file does not hold is not read.
        let path = file("other.csv", THIRTY, 3000.0, 3.0);
        let none = read_all(std::slice::from_ref(&path), &[MODE], 3.0).unwrap();
        std::fs::remove_file(&path).unwrap();
        assert!(none.is_empty());
    }

    #[test]
    fn a_scene_whose_label_holds_commas_is_written_quoted_and_read_back() {
        let shake = Scene::Shake {
            amplitude: 0.1,
            frequency: 2.0,
            start: crate::model::ShakeStart::Rest,
        };
        assert!(shake.to_string().contains(','));
        let path = file("shake.csv", shake, 3000.0, 3.0);
        let text = std::fs::read_to_string(&path).unwrap();
        let read = read_all(std::slice::from_ref(&path), &[THIRTY, shake], 3.0).unwrap();
        std::fs::remove_file(&path).unwrap();
        assert!(text.lines().nth(1).unwrap().starts_with('"'), "{text:.80}");
        assert_eq!(read.len(), 1);
        assert_eq!(read[0].scene, shake);
        assert!((read[0].tip_at(1.5) - Point::new(1.5f64.cos(), 1.5f64.sin())).norm() < 1e-8);
    }

    #[test]
    fn a_file_whose_rows_miss_frames_or_end_early_is_refused_with_what_would_do() {
        for (name, rate, until, says) in [
            (
                "thousandths.csv",
                1000.0,
                3.0,
                "1/1000 of a time unit apart",
            ),
            ("short.csv", 3000.0, 2.0, "end at t = 2"),
        ] {
            let path = file(name, THIRTY, rate, until);
            let err = read_all(std::slice::from_ref(&path), &[THIRTY], 3.0).unwrap_err();
            std::fs::remove_file(&path).unwrap();
            let text = err.to_string();
            assert!(text.contains(says), "{text}");
            assert!(text.contains("a row at every 1/3000"), "{text}");
            assert!(text.starts_with("references = "), "{text}");
        }
        let path = std::env::temp_dir().join(format!("rope-read-{}-bad.csv", std::process::id()));
        std::fs::write(&path, "t,x\n0,1\n").unwrap();
        let err = read_all(std::slice::from_ref(&path), &[THIRTY], 3.0).unwrap_err();
        std::fs::remove_file(&path).unwrap();
        assert!(err.to_string().contains("not the header"), "{err}");
    }
}
