//! Draws the committed release atlas (`assets/release-atlas/atlas.csv`) as
//! `assets/release-atlas/atlas.png` and `.svg`, and prints its margin and a Markdown table of
//! its trusted entries (what `docs/measurements.md` quotes); run by
//! `scripts/release-atlas.sh` after the atlas is measured. `release_atlas_chart graded`: the
//! graded rods' (`graded-atlas.csv`, `graded-atlas.png` and `.svg`).

use anyhow::Context;
use rope::plan::atlas::{Atlas, REFERENCE_MARGIN};
use std::path::Path;

fn main() -> anyhow::Result<()> {
    let (name, rods) = match std::env::args().nth(1).as_deref() {
        None => ("atlas", "the rods'"),
        Some("graded") => ("graded-atlas", "the graded rods'"),
        Some(other) => anyhow::bail!("usage: release_atlas_chart [graded] ({other:?} given)"),
    };
    let dir = Path::new("assets/release-atlas");
    let path = dir.join(format!("{name}.csv"));
    let text =
        std::fs::read_to_string(&path).with_context(|| format!("reading {}", path.display()))?;
    let atlas = Atlas::parse(&text)?;
    rope::study::charts::register_font()?;
    rope::study::atlas_chart::write(dir, name, rods, &atlas)?;
    println!(
        "the margin the held-out angles measure: {:.3}\n",
        atlas.margin
    );
    print!("{}", table(&text));
    Ok(())
}

/// The columns of the table: the atlas's N, every other one or so.
const COLUMNS: [usize; 8] = [16, 32, 64, 141, 283, 566, 800, 1131];

/// Each atlas angle's reference (N, own error) and worst tip error × N where the atlas trusts
/// it (the reference's own error at most [`REFERENCE_MARGIN`] of it, from N = 16 up to the
/// first it does not), as a Markdown table of the [`COLUMNS`] the atlas measured.
fn table(csv: &str) -> String {
    let measured = |n: &usize| {
        csv.lines()
            .any(|line| line.split(',').nth(2) == Some(n.to_string().as_str()))
    };
    let mut out = String::from("| angle | reference (N) | own error |");
    let mut rule = String::from("|---|---|---|");
    for n in COLUMNS.iter().filter(|n| measured(n)) {
        out += &format!(" N = {n} |");
        rule += "---|";
    }
    out += &format!("\n{rule}\n");
    // (angle, reference N, own error, [worst × N or None]) per atlas angle, in file order.
    let mut rows: Vec<(String, String, String, Vec<Option<f64>>)> = Vec::new();
    let mut gap = false;
    for line in csv.lines().skip(1) {
        let fields: Vec<&str> = line.split(',').collect();
        let [set, angle, segments, worst, reference, own] = fields.as_slice() else {
            continue;
        };
        if *set != "atlas" {
            continue;
        }
        if rows.last().is_none_or(|r| r.0 != *angle) {
            rows.push((
                angle.to_string(),
                reference.to_string(),
                own.to_string(),
                vec![],
            ));
            gap = false;
        }
        let (worst, own): (f64, f64) = (
            worst.parse().unwrap_or(f64::NAN),
            own.parse().unwrap_or(f64::NAN),
        );
        gap |= !(worst.is_finite() && own <= REFERENCE_MARGIN * worst);
        let n: usize = segments.parse().unwrap_or(0);
        if let (Some(row), true) = (rows.last_mut(), COLUMNS.contains(&n)) {
            row.3.push((!gap).then_some(worst * n as f64));
        }
    }
    for (angle, reference, own, entries) in rows {
        let own: f64 = own.parse().unwrap_or(f64::NAN);
        out += &format!("| {angle}° | {reference} | {own:.1e} |");
        for entry in entries {
            out += &entry.map_or(" – |".to_owned(), |c| format!(" {c:.3} |"));
        }
        out += "\n";
    }
    out
}
