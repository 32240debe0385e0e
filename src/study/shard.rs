//! A study split over processes or machines. `--shard I/N` runs the cells of the grid whose
//! place in its fixed order is I modulo N, and writes a partial `study.csv` beside a manifest,
//! `shard.json` (the grid, the shard, the reference). `--reference-only` computes the
//! reference once (`reference.json`) for every shard to share. `--merge DIR…` checks that the
//! shards are of one study and cover its grid exactly once, then builds the whole study.

use super::grid::{Row, Spec, sort_rows};
use super::reference::Reference;
use super::trajectory::Trajectory;
use crate::methods::MethodKind;
use crate::model::{Point, Scene};
use std::path::{Path, PathBuf};

/// The manifest beside a shard's `study.csv`.
pub const MANIFEST: &str = "shard.json";
/// The file `--reference-only` writes.
pub const REFERENCE: &str = "reference.json";

/// Shard `index` of `count`: the cells whose place in [`Spec::cells`] is `index` mod `count`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

impl std::str::FromStr for Shard {
    type Err = String;

    /// `I/N`, with 0 ≤ I < N.
    fn from_str(text: &str) -> Result<Self, String> {
        let bad = || format!("{text:?} is not a shard: give I/N with 0 ≤ I < N, e.g. 0/8");
        let (i, n) = text.split_once('/').ok_or_else(bad)?;
        let (index, count) = (
            i.trim().parse().map_err(|_| bad())?,
            n.trim().parse().map_err(|_| bad())?,
        );
        if count == 0 || index >= count {
            return Err(bad());
        }
        Ok(Self { index, count })
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

impl Shard {
    /// This shard's cells of `spec`'s grid.
    pub fn cells(&self, spec: &Spec) -> Vec<(MethodKind, usize, f64)> {
        spec.cells()
            .into_iter()
            .enumerate()
            .filter(|(i, _)| i % self.count == self.index)
            .map(|(_, cell)| cell)
            .collect()
    }
}

/// A cell in words, for messages: "chain N = 50 k = 1e-3".
fn cell_text(&(method, segments, dt): &(MethodKind, usize, f64)) -> String {
    format!("{method} N = {segments} k = {dt:e}")
}

/// The reference as a file: what it is of, and what it found.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ReferenceFile {
    pub scene: Scene,
    pub duration: f64,
    pub finest: usize,
    pub tip: [f64; 2],
    pub shape: Vec<[f64; 2]>,
    pub error_in_h: f64,
    pub error_in_k: f64,
    pub description: String,
    /// The step between the points of `path`.
    pub path_dt: f64,
    /// The reference's tip at every step from t = 0, what frames are measured against.
    pub path: Vec<[f64; 2]>,
}

impl ReferenceFile {
    /// `reference` of `scene` to `duration` at `finest` segments, as a file.
    pub fn new(scene: Scene, duration: f64, finest: usize, reference: &Reference) -> Self {
        Self {
            scene,
            duration,
            finest,
            tip: [reference.tip.x, reference.tip.y],
            shape: reference.shape.iter().map(|p| [p.x, p.y]).collect(),
            error_in_h: reference.error_in_h,
            error_in_k: reference.error_in_k,
            description: reference.description.clone(),
            path_dt: reference.path.dt(),
            path: reference.path.tips().iter().map(|p| [p.x, p.y]).collect(),
        }
    }

    /// The reference it holds.
    pub fn reference(&self) -> Reference {
        Reference {
            tip: Point::new(self.tip[0], self.tip[1]),
            shape: self.shape.iter().map(|p| Point::new(p[0], p[1])).collect(),
            error_in_h: self.error_in_h,
            error_in_k: self.error_in_k,
            description: self.description.clone(),
            path: Trajectory::new(
                self.path_dt,
                self.path.iter().map(|p| Point::new(p[0], p[1])).collect(),
            ),
        }
    }
}

/// What a shard's directory says of itself.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Manifest {
    pub shard: Shard,
    pub spec: Spec,
    pub reference: ReferenceFile,
}

/// Why shards cannot be merged: each names the shards or cells at fault.
#[derive(Debug, thiserror::Error)]
pub enum MergeError {
    #[error("--merge: no shard directories given")]
    Nothing,
    #[error("--merge: {dir}: {reason}")]
    Unreadable { dir: PathBuf, reason: String },
    #[error(
        "--merge: {dir} is shard {shard} of another study than {first} (its {what} differs); merge the shards of one `rope study --shard I/N` command line"
    )]
    OtherStudy {
        dir: PathBuf,
        shard: Shard,
        first: PathBuf,
        what: &'static str,
    },
    #[error("--merge: shard {shard} is given twice, in {first} and {second}; give each once")]
    Duplicate {
        shard: Shard,
        first: PathBuf,
        second: PathBuf,
    },
    #[error(
        "--merge: shard{plural} {missing} of {count} missing, so these cells have no row: {cells}; run `rope study --shard I/{count}` for each and merge again"
    )]
    Missing {
        missing: String,
        plural: &'static str,
        count: usize,
        cells: String,
    },
    #[error(
        "--merge: {dir} (shard {shard}) does not hold its cells exactly: missing {missing}; not its own {extra}; run that shard again"
    )]
    Incomplete {
        dir: PathBuf,
        shard: Shard,
        missing: String,
        extra: String,
    },
}

/// Reads `dir`'s manifest and rows.
fn read_shard(dir: &Path) -> Result<(Manifest, Vec<Row>), MergeError> {
    let unreadable = |reason: String| MergeError::Unreadable {
        dir: dir.to_owned(),
        reason,
    };
    let manifest = dir.join(MANIFEST);
    let text = std::fs::read_to_string(&manifest).map_err(|e| {
        unreadable(format!(
            "{} cannot be read ({e}); is it the --out of `rope study --shard I/N`?",
            manifest.display()
        ))
    })?;
    let manifest: Manifest = serde_json::from_str(&text).map_err(|e| {
        unreadable(format!(
            "{} is not a shard manifest: {e}",
            manifest.display()
        ))
    })?;
    let csv = dir.join("study.csv");
    let rows =
        super::report::read_csv(&csv).map_err(|e| unreadable(format!("{}: {e}", csv.display())))?;
    Ok((manifest, rows))
}

/// Whether `row` is the run of `cell`.
fn is_cell(row: &Row, &(method, segments, dt): &(MethodKind, usize, f64)) -> bool {
    row.method == method && row.segments == segments && (row.dt / dt - 1.0).abs() < 1e-12
}

/// The shards in `dirs`, checked and put together: the study's grid, its reference, and every
/// row, sorted as a whole study sorts them.
pub fn merge(dirs: &[PathBuf]) -> Result<(Spec, ReferenceFile, Vec<Row>), MergeError> {
    let mut shards: Vec<(PathBuf, Manifest, Vec<Row>)> = Vec::new();
    for dir in dirs {
        let (manifest, rows) = read_shard(dir)?;
        if let Some((first, m, _)) = shards.first() {
            let what = if m.spec != manifest.spec {
                Some("grid")
            } else if m.shard.count != manifest.shard.count {
                Some("number of shards")
            } else if m.reference != manifest.reference {
                Some("reference")
            } else {
                None
            };
            if let Some(what) = what {
                return Err(MergeError::OtherStudy {
                    dir: dir.clone(),
                    shard: manifest.shard,
                    first: first.clone(),
                    what,
                });
            }
        }
        if let Some((first, ..)) = shards.iter().find(|(_, m, _)| m.shard == manifest.shard) {
            return Err(MergeError::Duplicate {
                shard: manifest.shard,
                first: first.clone(),
                second: dir.clone(),
            });
        }
        shards.push((dir.clone(), manifest, rows));
    }
    let Some((_, first, _)) = shards.first() else {
        return Err(MergeError::Nothing);
    };
    let (spec, reference, count) = (
        first.spec.clone(),
        first.reference.clone(),
        first.shard.count,
    );
    let missing: Vec<usize> = (0..count)
        .filter(|&i| !shards.iter().any(|(_, m, _)| m.shard.index == i))
        .collect();
    if !missing.is_empty() {
        let cells: Vec<String> = missing
            .iter()
            .flat_map(|&index| Shard { index, count }.cells(&spec))
            .map(|c| cell_text(&c))
            .collect();
        return Err(MergeError::Missing {
            missing: missing
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join(", "),
            plural: if missing.len() > 1 { "s" } else { "" },
            count,
            cells: cells.join(", "),
        });
    }
    let mut all = Vec::new();
    for (dir, manifest, rows) in shards {
        let cells = manifest.shard.cells(&spec);
        let absent: Vec<String> = cells
            .iter()
            .filter(|c| rows.iter().filter(|r| is_cell(r, c)).count() != 1)
            .map(cell_text)
            .collect();
        let extra: Vec<String> = rows
            .iter()
            .filter(|r| !cells.iter().any(|c| is_cell(r, c)))
            .map(|r| cell_text(&(r.method, r.segments, r.dt)))
            .collect();
        if !absent.is_empty() || !extra.is_empty() || rows.len() != cells.len() {
            let list = |v: Vec<String>| {
                if v.is_empty() {
                    "none".to_owned()
                } else {
                    v.join(", ")
                }
            };
            return Err(MergeError::Incomplete {
                dir,
                shard: manifest.shard,
                missing: list(absent),
                extra: list(extra),
            });
        }
        all.extend(rows);
    }
    sort_rows(&mut all);
    Ok((spec, reference, all))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_shard_is_written_i_slash_n_and_must_be_one_of_n() {
        assert_eq!("2/8".parse(), Ok(Shard { index: 2, count: 8 }));
        for bad in ["8/8", "1/0", "a/2", "3", "-1/2"] {
            assert!(bad.parse::<Shard>().is_err(), "{bad}");
        }
    }

    #[test]
    fn the_shards_of_a_grid_cover_every_cell_once() {
        let spec = Spec {
            scene: Scene::Release { angle_deg: 30.0 },
            duration: 1.0,
            methods: MethodKind::ALL.to_vec(),
            segments: vec![10, 20, 50],
            dts: vec![1e-3, 1e-2],
        };
        let all = spec.cells();
        let mut covered: Vec<_> = (0..4)
            .flat_map(|index| Shard { index, count: 4 }.cells(&spec))
            .collect();
        assert_eq!(covered.len(), all.len());
        covered.sort_by_key(cell_text);
        let mut sorted = all.clone();
        sorted.sort_by_key(cell_text);
        assert_eq!(covered, sorted);
    }
}
