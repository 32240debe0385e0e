//! Draws the committed release atlas (`assets/release-atlas/atlas.csv`) as
//! `assets/release-atlas/atlas.png` and `.svg`, and prints its margin; run by
//! `scripts/release-atlas.sh` after the atlas is measured. `release_atlas_chart graded`: the
//! graded rods' (`graded-atlas.csv`, `graded-atlas.png` and `.svg`).

use anyhow::Context;
use rope::plan::atlas::Atlas;
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
        "the margin the held-out angles measure: {:.3}",
        atlas.margin
    );
    Ok(())
}
