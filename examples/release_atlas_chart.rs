//! Draws the committed release atlas (`assets/release-atlas/atlas.csv`) as
//! `assets/release-atlas/atlas.png` and `.svg`, and prints its margin and a Markdown table of
//! its trusted entries (what `docs/measurements.md` quotes); run by
//! `scripts/release-atlas.sh` after the atlas is measured. `release_atlas_chart graded`: the
//! graded rods' (`graded-atlas.csv`, `graded-atlas.png` and `.svg`); `release_atlas_chart
//! graded --until 5`: theirs to t = 5 (`graded-atlas-t5.csv`, `.png`, `.svg`).

use anyhow::Context;
use rope::plan::atlas::{Atlas, LONGER_WINDOW, WINDOW};
use std::collections::HashMap;
use std::path::Path;

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let (name, rods, window) = match args.as_slice() {
        [] => ("atlas", "the rods'", WINDOW),
        ["graded"] => ("graded-atlas", "the graded rods'", WINDOW),
        ["graded", "--until", "5"] => ("graded-atlas-t5", "the graded rods'", LONGER_WINDOW),
        other => anyhow::bail!("usage: release_atlas_chart [graded [--until 5]] ({other:?} given)"),
    };
    let dir = Path::new("assets/release-atlas");
    let path = dir.join(format!("{name}.csv"));
    let text =
        std::fs::read_to_string(&path).with_context(|| format!("reading {}", path.display()))?;
    let atlas = Atlas::parse(&text, window)?;
    rope::study::charts::register_font()?;
    rope::study::atlas_chart::write(dir, name, rods, &atlas)?;
    println!(
        "the margin the held-out angles measure: {:.3}; the envelope's: {:.3}\n",
        atlas.margin, atlas.envelope_margin
    );
    print!("{}", table(&text, &atlas));
    Ok(())
}

/// The columns of the table: the atlas's N, every other one or so.
const COLUMNS: [usize; 10] = [16, 32, 64, 141, 283, 566, 800, 1131, 1600, 2263];

/// Each atlas angle's reference (N, own error) and worst tip error × N, in parentheses where
/// the atlas does not trust it ([`Atlas::rows`]: below ten times its reference's own error), as
/// a Markdown table of the [`COLUMNS`] the atlas measured. The worst errors, the references' N
/// and own errors are read from the atlas's `csv`.
fn table(csv: &str, atlas: &Atlas) -> String {
    // (angle, N) → (worst, reference N, own error), of the atlas's angles.
    let mut measured: HashMap<(String, usize), (f64, String, f64)> = HashMap::new();
    for line in csv.lines().skip(1) {
        let fields: Vec<&str> = line.split(',').collect();
        let ["atlas", angle, segments, worst, reference, own] = fields.as_slice() else {
            continue;
        };
        let (Ok(n), Ok(worst), Ok(own)) = (segments.parse(), worst.parse(), own.parse()) else {
            continue;
        };
        measured.insert((angle.to_string(), n), (worst, reference.to_string(), own));
    }
    let columns: Vec<usize> = COLUMNS
        .into_iter()
        .filter(|&n| measured.keys().any(|&(_, m)| m == n))
        .collect();
    let mut out = String::from("| angle | reference (N) | own error |");
    let mut rule = String::from("|---|---|---|");
    for n in &columns {
        out += &format!(" N = {n} |");
        rule += "---|";
    }
    out += &format!("\n{rule}\n");
    for (angle_deg, trusted) in atlas.rows() {
        let angle = angle_deg.to_string();
        let Some((_, reference, own)) = columns
            .first()
            .and_then(|&n| measured.get(&(angle.clone(), n)))
        else {
            continue;
        };
        out += &format!("| {angle}° | {reference} | {own:.1e} |");
        for &n in &columns {
            let worst = measured.get(&(angle.clone(), n)).map(|m| m.0);
            let entry = match (trusted.iter().any(|&(m, _)| m == n), worst) {
                (true, Some(worst)) => format!(" {:.3} |", worst * n as f64),
                (false, Some(worst)) => format!(" ({:.3}) |", worst * n as f64),
                _ => " – |".to_owned(),
            };
            out += &entry;
        }
        out += "\n";
    }
    out
}
