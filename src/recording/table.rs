//! `rope run --table FILE`: the run's frames as tidy tables that a data frame reads in one
//! line, CSV or Parquet by the file's extension. Two tables:
//!
//! * the **series**, at `FILE`: a row per frame (and per method, side by side);
//! * the **tension profiles**, beside it at `FILE`'s stem + `-profiles`: a row per point of
//!   each frame's profile, the support first.
//!
//! Every value is a float64 but `scene` and `method`; lengths in L, time in sqrt(L/g), energy
//! in m g L, force in m g; x is horizontal away from the support and **y points down**. The
//! columns are [`SERIES`], [`SHAKE_SERIES`] (a shake's, after the series') and [`PROFILES`].
//! Rows are written as the run makes them, so a run that diverges or is stopped keeps every
//! row before; a Parquet file gets its footer when the run ends ([`Tables::finish`]).

use crate::model::geometry::Point;
use crate::run::{Frame, FrameSink, RunPlan};
use arrow_array::{ArrayRef, Float64Array, RecordBatch, StringArray};
use arrow_schema::{DataType, Field, Schema};
use std::fs::File;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The series' columns, each with what it holds.
pub const SERIES: [(&str, &str); 13] = [
    ("time", "t, in sqrt(L/g)"),
    ("scene", "the scene, as the caption names it"),
    ("method", "the numerical method"),
    (
        "tip_x",
        "the free end's x, horizontal away from the support",
    ),
    ("tip_y", "the free end's y, pointing down"),
    ("tip_speed", "the free end's speed"),
    ("kinetic_energy", "translational and rotational"),
    ("potential_energy", "−Σ m g y_i"),
    ("energy", "kinetic + potential (in the room, for a shake)"),
    (
        "energy_deviation",
        "(E − W − E_ref)/|E_ref|, E_ref after 10 steps",
    ),
    ("support_tension", "the pull at the support, F(0)"),
    (
        "tip_error_estimate",
        "the live estimate of the tip's error; empty where none",
    ),
    ("support_x", "where the support is (0 unless it is shaken)"),
];

/// A shake's further columns.
pub const SHAKE_SERIES: [(&str, &str); 2] = [
    (
        "support_work",
        "the work W the support has done since the start",
    ),
    ("balance", "E − E₀ − W: zero for the ideal string"),
];

/// The profiles' columns.
pub const PROFILES: [(&str, &str); 7] = [
    ("time", "t"),
    ("scene", "the scene"),
    ("method", "the numerical method"),
    ("s", "arc length from the support, 0 … 1"),
    ("x", "the string's x there"),
    ("y", "the string's y there, pointing down"),
    ("tension", "F(s), in m g"),
];

/// The format of a table, from its file's extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Csv,
    Parquet,
}

/// Why the tables could not be written.
#[derive(Debug, thiserror::Error)]
pub enum TableError {
    #[error(
        "--table {0}: the extension says the format; use .csv or .parquet (for example --table run.csv)"
    )]
    Extension(PathBuf),
    #[error("--table: cannot create {path}: {source}")]
    Create {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error("writing the table {path}: {reason}")]
    Write { path: PathBuf, reason: String },
}

impl Format {
    /// The format `path`'s extension names.
    pub fn of(path: &Path) -> Result<Self, TableError> {
        match path.extension().and_then(|e| e.to_str()) {
            Some(e) if e.eq_ignore_ascii_case("csv") => Ok(Self::Csv),
            Some(e) if e.eq_ignore_ascii_case("parquet") => Ok(Self::Parquet),
            _ => Err(TableError::Extension(path.to_owned())),
        }
    }
}

/// Where the profiles of a series at `series` go: beside it, its stem + `-profiles`.
pub fn profiles_path(series: &Path) -> PathBuf {
    let stem = series.file_stem().unwrap_or_default().to_string_lossy();
    let ext = series.extension().unwrap_or_default().to_string_lossy();
    series.with_file_name(format!("{stem}-profiles.{ext}"))
}

/// A column's values in one batch of rows.
enum Values {
    Text(Vec<String>),
    Number(Vec<Option<f64>>),
}

/// Columns of one batch of rows, in a table's order.
struct Batch {
    columns: Vec<(&'static str, Values)>,
}

impl Batch {
    /// Empty columns named as `columns`, those named in `texts` text, the others numbers.
    fn new(columns: &[(&'static str, &str)], texts: &[&str]) -> Self {
        let columns = columns
            .iter()
            .map(|&(name, _)| match texts.contains(&name) {
                true => (name, Values::Text(Vec::new())),
                false => (name, Values::Number(Vec::new())),
            })
            .collect();
        Self { columns }
    }

    /// Adds a row: `texts` to the text columns and `numbers` to the number columns, each in
    /// the table's order.
    fn push<'a>(
        &mut self,
        texts: impl IntoIterator<Item = &'a str>,
        numbers: impl IntoIterator<Item = Option<f64>>,
    ) {
        let (mut texts, mut numbers) = (texts.into_iter(), numbers.into_iter());
        for (_, values) in &mut self.columns {
            match values {
                Values::Text(v) => v.push(texts.next().unwrap_or_default().to_owned()),
                Values::Number(v) => v.push(numbers.next().flatten()),
            }
        }
    }

    fn len(&self) -> usize {
        match self.columns.first() {
            Some((_, Values::Text(v))) => v.len(),
            Some((_, Values::Number(v))) => v.len(),
            None => 0,
        }
    }

    fn clear(&mut self) {
        for (_, values) in &mut self.columns {
            match values {
                Values::Text(v) => v.clear(),
                Values::Number(v) => v.clear(),
            }
        }
    }

    fn schema(&self) -> Arc<Schema> {
        let fields: Vec<Field> = self
            .columns
            .iter()
            .map(|(name, values)| match values {
                Values::Text(_) => Field::new(*name, DataType::Utf8, false),
                Values::Number(_) => Field::new(*name, DataType::Float64, true),
            })
            .collect();
        Arc::new(Schema::new(fields))
    }

    /// The rows gathered so far as Arrow arrays, the batch left empty.
    fn take_record_batch(&mut self, schema: Arc<Schema>) -> Result<RecordBatch, String> {
        let arrays: Vec<ArrayRef> = self
            .columns
            .iter_mut()
            .map(|(_, values)| -> ArrayRef {
                match values {
                    Values::Text(v) => Arc::new(StringArray::from(std::mem::take(v))),
                    Values::Number(v) => Arc::new(Float64Array::from(std::mem::take(v))),
                }
            })
            .collect();
        RecordBatch::try_new(schema, arrays).map_err(|e| e.to_string())
    }

    /// Row `r` as CSV fields (an empty field for a missing number).
    fn csv_row(&self, r: usize) -> Vec<String> {
        self.columns
            .iter()
            .map(|(_, values)| match values {
                Values::Text(v) => v[r].clone(),
                Values::Number(v) => v[r].map_or(String::new(), csv_number),
            })
            .collect()
    }
}

/// A number as a CSV field, read back bit for bit: the shortest decimal that round-trips, in
/// scientific notation where plain digits would run long (1.5e-19, not 0.000…00015).
fn csv_number(value: f64) -> String {
    let magnitude = value.abs();
    if magnitude == 0.0 || (1e-4..1e15).contains(&magnitude) || !value.is_finite() {
        value.to_string()
    } else {
        format!("{value:e}")
    }
}

/// Where one table's rows go.
enum Writer {
    Csv(Box<csv::Writer<File>>),
    Parquet(Box<parquet::arrow::ArrowWriter<File>>),
}

/// One table: its file and its writer.
struct Table {
    path: PathBuf,
    writer: Writer,
    batch: Batch,
}

impl Table {
    fn create(path: PathBuf, format: Format, batch: Batch) -> Result<Self, TableError> {
        let file = File::create(&path).map_err(|source| TableError::Create {
            path: path.clone(),
            source,
        })?;
        let writer = match format {
            Format::Csv => {
                let mut writer = csv::Writer::from_writer(file);
                let header: Vec<String> = batch
                    .schema()
                    .fields()
                    .iter()
                    .map(|f| f.name().clone())
                    .collect();
                writer
                    .write_record(&header)
                    .map_err(|e| write_error(&path, e))?;
                Writer::Csv(Box::new(writer))
            }
            Format::Parquet => {
                let properties = parquet::file::properties::WriterProperties::builder()
                    .set_compression(parquet::basic::Compression::SNAPPY)
                    .build();
                let writer =
                    parquet::arrow::ArrowWriter::try_new(file, batch.schema(), Some(properties))
                        .map_err(|e| write_error(&path, e))?;
                Writer::Parquet(Box::new(writer))
            }
        };
        Ok(Self {
            path,
            writer,
            batch,
        })
    }

    /// Writes the rows gathered so far.
    fn write(&mut self) -> Result<(), TableError> {
        let rows = self.batch.len();
        if rows == 0 {
            return Ok(());
        }
        match &mut self.writer {
            Writer::Csv(w) => {
                for r in 0..rows {
                    w.write_record(self.batch.csv_row(r))
                        .map_err(|e| write_error(&self.path, e))?;
                }
                w.flush().map_err(|e| write_error(&self.path, e))?;
            }
            Writer::Parquet(w) => {
                let schema = self.batch.schema();
                let batch = self
                    .batch
                    .take_record_batch(schema)
                    .map_err(|e| write_error(&self.path, e))?;
                w.write(&batch).map_err(|e| write_error(&self.path, e))?;
            }
        }
        self.batch.clear();
        Ok(())
    }

    /// Ends the file (a Parquet file's footer).
    fn finish(mut self) -> Result<(), TableError> {
        self.write()?;
        match self.writer {
            Writer::Csv(mut w) => w.flush().map_err(|e| write_error(&self.path, e)),
            Writer::Parquet(w) => w.close().map(drop).map_err(|e| write_error(&self.path, e)),
        }
    }
}

fn write_error(path: &Path, reason: impl std::fmt::Display) -> TableError {
    TableError::Write {
        path: path.to_owned(),
        reason: reason.to_string(),
    }
}

/// The two tables of a run, a [`FrameSink`].
pub struct Tables {
    series: Table,
    profiles: Table,
    /// Whether the series carries a shake's columns.
    shake: bool,
    /// Each lane's scene and method, as the rows name them.
    names: Vec<(String, &'static str)>,
}

impl Tables {
    /// Creates the tables at `path` (the series) and beside it (the profiles); `shakes` (a
    /// run whose support is shaken) adds the shake's columns to the series.
    pub fn create(path: &Path, shakes: bool) -> Result<Self, TableError> {
        let format = Format::of(path)?;
        let mut series_columns: Vec<(&'static str, &str)> = SERIES.to_vec();
        if shakes {
            series_columns.extend_from_slice(&SHAKE_SERIES);
        }
        let texts = ["scene", "method"];
        let series = Table::create(path.to_owned(), format, Batch::new(&series_columns, &texts))?;
        let profiles = Table::create(profiles_path(path), format, Batch::new(&PROFILES, &texts))?;
        Ok(Self {
            series,
            profiles,
            shake: shakes,
            names: Vec::new(),
        })
    }

    /// Ends both files: what a Parquet file needs to be read. Call once, after the last run.
    pub fn finish(self) -> Result<(), TableError> {
        self.series.finish()?;
        self.profiles.finish()
    }

    fn take(&mut self, frame: &Frame) {
        let lane = frame.lane.map_or(0, |l| l.index);
        let (scene, method) = self
            .names
            .get(lane)
            .cloned()
            .unwrap_or_else(|| (String::new(), ""));
        let tip = frame.tip();
        let support = frame.support;
        let numbers = [
            Some(frame.time),
            Some(tip.x),
            Some(tip.y),
            Some(frame.tip_velocity.norm()),
            Some(frame.energy.kinetic()),
            Some(frame.energy.potential),
            Some(frame.energy.total()),
            Some(frame.energy_deviation),
            Some(frame.support_tension),
            frame.error_estimate.map(|e| e.tip),
            Some(support.map_or(0.0, |s| s.position)),
        ];
        let shake = self
            .shake
            .then_some([support.map(|s| s.work), frame.balance]);
        let texts = [scene.as_str(), method];
        self.series.batch.push(
            texts,
            numbers.into_iter().chain(shake.into_iter().flatten()),
        );
        let profiles = &mut self.profiles.batch;
        let mut row = |s: f64, at: Point, tension: f64| {
            profiles.push(texts, [frame.time, s, at.x, at.y, tension].map(Some));
        };
        let support_point = frame.nodes.first().copied().unwrap_or_else(Point::origin);
        row(0.0, support_point, frame.support_tension);
        let mut along = Along::new(frame);
        for (i, &tension) in frame.tension.iter().enumerate() {
            let s = frame.tension_s(i);
            row(s, along.point_at(s), tension);
        }
    }
}

/// A walk down a frame's string, for its points at increasing arc length.
struct Along<'a> {
    frame: &'a Frame,
    segments: usize,
    /// The segment the last point was on.
    at: usize,
}

impl<'a> Along<'a> {
    fn new(frame: &'a Frame) -> Self {
        Self {
            frame,
            segments: frame.nodes.len().saturating_sub(1),
            at: 0,
        }
    }

    /// Where node `j` sits along the string.
    fn edge(&self, j: usize) -> f64 {
        match &self.frame.edges {
            Some(e) => e[j],
            None => j as f64 / self.segments as f64,
        }
    }

    /// The string's point at arc length `s` (no less than the last asked), on the straight
    /// segment between two nodes.
    fn point_at(&mut self, s: f64) -> Point {
        let nodes = &self.frame.nodes;
        if self.segments == 0 {
            return nodes.first().copied().unwrap_or_else(Point::origin);
        }
        while self.at + 1 < self.segments && s > self.edge(self.at + 1) {
            self.at += 1;
        }
        let j = self.at;
        let (from, to) = (self.edge(j), self.edge(j + 1));
        let fraction = if to > from {
            (s - from) / (to - from)
        } else {
            0.0
        };
        nodes[j] + (nodes[j + 1] - nodes[j]) * fraction.clamp(0.0, 1.0)
    }
}

impl FrameSink for Tables {
    type Error = TableError;

    fn begin_run(&mut self, plan: &RunPlan) -> Result<(), TableError> {
        self.names = vec![(plan.scene.to_string(), plan.method.name())];
        Ok(())
    }

    fn begin_lanes(&mut self, plans: &[RunPlan]) -> Result<(), TableError> {
        self.names = plans
            .iter()
            .map(|p| (p.scene.to_string(), p.method.name()))
            .collect();
        Ok(())
    }

    fn frames(&mut self, frames: &[Frame]) -> Result<(), TableError> {
        frames.iter().for_each(|f| self.take(f));
        self.series.write()?;
        self.profiles.write()
    }

    fn flush(&mut self) -> Result<(), TableError> {
        self.series.write()?;
        self.profiles.write()
    }

    fn end_run(&mut self, _time: f64, _steps: u64) {}
}
