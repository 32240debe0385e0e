//! `rope run --table FILE`: the series and the tension profiles as CSV and as Parquet, read
//! back here with the same crates a reader would use, against the run's own summary and the
//! physics of the scene (a chain released from the horizontal falls freely, y down, until
//! the bend reaches its tip).

mod common;

use arrow_array::{Array, Float64Array, RecordBatch};
use common::cli::{Scratch, rope, summary};
use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;
use rope::recording::table::{PROFILES, SERIES, SHAKE_SERIES, profiles_path};
use std::path::Path;

/// The CSV at `path`: its header and its rows.
fn read_csv(path: &Path) -> (Vec<String>, Vec<csv::StringRecord>) {
    let mut reader = csv::Reader::from_path(path).expect("the CSV table");
    let header = reader
        .headers()
        .unwrap()
        .iter()
        .map(str::to_owned)
        .collect();
    (header, reader.records().map(Result::unwrap).collect())
}

/// The Parquet file at `path`, as one batch (a batch large enough for any table here).
fn read_parquet(path: &Path) -> RecordBatch {
    let file = std::fs::File::open(path).expect("the Parquet table");
    let mut reader = ParquetRecordBatchReaderBuilder::try_new(file)
        .unwrap()
        .with_batch_size(1 << 24)
        .build()
        .unwrap();
    let batch = reader.next().expect("a batch").unwrap();
    assert!(reader.next().is_none(), "more rows than one batch holds");
    batch
}

fn column<'a>(batch: &'a RecordBatch, name: &str) -> &'a Float64Array {
    batch
        .column_by_name(name)
        .unwrap_or_else(|| panic!("no column {name}"))
        .as_any()
        .downcast_ref::<Float64Array>()
        .unwrap_or_else(|| panic!("{name} is not float64"))
}

/// The chain from the horizontal, N = 100, to t = 1: the series has a row per frame with the
/// columns docs/data.md names, its tip falls as t²/2 (y down) to round-off before the bend
/// arrives, the CSV and the Parquet hold the same numbers bit for bit, and the profiles run
/// from the support (the summary's pull there) down the string, one per frame.
#[test]
fn a_release_written_as_csv_and_as_parquet_reads_back_as_the_run() {
    let dir = Scratch::new("tables");
    let run = |table: &str| {
        let json = dir.path("run.json");
        let out = rope(&[
            "run",
            "--method",
            "chain",
            "--angle",
            "0",
            "--duration",
            "1",
            "--log-rate",
            "20",
            "--save",
            dir.path("run.rrd").to_str().unwrap(),
            "--summary",
            json.to_str().unwrap(),
            "--table",
            dir.path(table).to_str().unwrap(),
        ]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        summary(&json)
    };
    let said = run("run.csv");
    run("run.parquet");
    let (header, rows) = read_csv(&dir.path("run.csv"));
    let names: Vec<&str> = SERIES.iter().map(|c| c.0).collect();
    assert_eq!(header, names);
    assert_eq!(rows.len() as u64, said["frames_logged"].as_u64().unwrap());
    let parquet = read_parquet(&dir.path("run.parquet"));
    assert_eq!(parquet.num_rows(), rows.len());
    for (i, &name) in names.iter().enumerate() {
        if name == "scene" || name == "method" {
            continue;
        }
        let values = column(&parquet, name);
        for (r, row) in rows.iter().enumerate() {
            let from_csv: Option<f64> = (!row[i].is_empty()).then(|| row[i].parse().unwrap());
            let from_parquet = values.is_valid(r).then(|| values.value(r));
            assert_eq!(from_csv, from_parquet, "{name} at row {r}");
        }
    }
    // Free fall, y down, until the bend reaches the tip (near t = 1.2).
    let (time, tip_y) = (column(&parquet, "time"), column(&parquet, "tip_y"));
    for r in 0..parquet.num_rows() {
        let t = time.value(r);
        assert!(
            (tip_y.value(r) - t * t / 2.0).abs() < 1e-9,
            "t = {t}: {}",
            tip_y.value(r)
        );
    }
    let profiles = read_parquet(&profiles_path(&dir.path("run.parquet")));
    let profile_names: Vec<String> = profiles
        .schema()
        .fields()
        .iter()
        .map(|f| f.name().clone())
        .collect();
    assert_eq!(
        profile_names,
        PROFILES.iter().map(|c| c.0).collect::<Vec<_>>()
    );
    assert_eq!(profiles.num_rows(), rows.len() * 101);
    let (s, tension) = (column(&profiles, "s"), column(&profiles, "tension"));
    let last = profiles.num_rows() - 101;
    assert_eq!(s.value(last), 0.0);
    assert_eq!(
        tension.value(last),
        said["support_tension"].as_f64().unwrap()
    );
    assert!((1..101).all(|i| s.value(last + i) > s.value(last + i - 1) && s.value(last + i) < 1.0));
}

/// A shake's series carries the support's work and the balance after the others; a file
/// whose extension names no format is refused before anything runs, saying what would work.
#[test]
fn a_shake_adds_its_columns_and_a_wrong_extension_is_refused() {
    let dir = Scratch::new("tables-shake");
    let table = dir.path("shake.csv");
    let out = rope(&[
        "run",
        "--scene",
        "shake",
        "--amplitude",
        "0.01",
        "--segments",
        "20",
        "--duration",
        "1",
        "--save",
        dir.path("shake.rrd").to_str().unwrap(),
        "--table",
        table.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let (header, rows) = read_csv(&table);
    let names: Vec<&str> = SERIES.iter().chain(&SHAKE_SERIES).map(|c| c.0).collect();
    assert_eq!(header, names);
    let balance = header.iter().position(|h| h == "balance").unwrap();
    assert!(
        rows.iter()
            .all(|r| r[balance].parse::<f64>().unwrap().abs() < 1e-12)
    );
    let out = rope(&["run", "--table", dir.path("x.txt").to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let said = String::from_utf8_lossy(&out.stderr);
    assert!(said.contains("use .csv or .parquet"), "{said}");
}

/// docs/data.md names every column the tables hold.
#[test]
fn the_data_guide_names_every_column() {
    let guide = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/data.md"))
        .expect("docs/data.md");
    for (name, _) in SERIES.iter().chain(&SHAKE_SERIES).chain(&PROFILES) {
        assert!(
            guide.contains(&format!("`{name}`")),
            "docs/data.md does not name {name}"
        );
    }
}
