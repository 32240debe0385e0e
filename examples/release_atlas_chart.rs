//! Draws the committed release atlas (`assets/release-atlas/atlas.csv`) as
//! `assets/release-atlas/atlas.png` and `.svg`, and prints its margin; run by
//! `scripts/release-atlas.sh` after the atlas is measured.

use anyhow::Context;
use rope::plan::atlas::Atlas;
use std::path::Path;

fn main() -> anyhow::Result<()> {
    let dir = Path::new("assets/release-atlas");
    let path = dir.join("atlas.csv");
    let text =
        std::fs::read_to_string(&path).with_context(|| format!("reading {}", path.display()))?;
    let atlas = Atlas::parse(&text)?;
    rope::study::charts::register_font()?;
    rope::study::atlas_chart::write(dir, &atlas)?;
    println!(
        "the margin the held-out angles measure: {:.3}",
        atlas.margin
    );
    Ok(())
}
