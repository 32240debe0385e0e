//! The release atlas: the worst tip error to t = 3 of the rods (the chain at its tolerance
//! step) from each release angle 0°, 10°, …, 90° at N = 16 … 566, against the chain
//! extrapolated from N = 800, 1600 and 3200; and the same at the held-out angles 5°, 15°, …,
//! 85°, which measure how far an angle between two of the atlas's can stray from them.
//! `scripts/release-atlas.sh` runs it (about 20 minutes on 2 cores) and writes
//! `assets/release-atlas/atlas.csv`, which `--tolerance` reads at build time
//! (`rope::plan::atlas`).

use rayon::prelude::*;
use rope::methods::MethodKind;
use rope::model::Scene;
use rope::plan::atlas::{ATLAS_ANGLES, HELD_OUT_ANGLES, SEGMENTS, WINDOW};
use rope::study::tolerance_check::{TipReference, measure};

/// The reference's N: runs at N/2, N and 2N.
const REFERENCE_SEGMENTS: usize = 1600;

fn main() -> anyhow::Result<()> {
    let angles: Vec<(&str, f64)> = ATLAS_ANGLES
        .iter()
        .map(|&a| ("atlas", a))
        .chain(HELD_OUT_ANGLES.iter().map(|&a| ("held-out", a)))
        .collect();
    let rows = angles
        .par_iter()
        .map(|&(set, angle_deg)| {
            let scene = Scene::Release { angle_deg };
            let reference = TipReference::compute(&scene, REFERENCE_SEGMENTS, WINDOW)?;
            let chain = MethodKind::Chain;
            let lines: Vec<String> = SEGMENTS
                .iter()
                .map(|&n| {
                    let dt = chain.tolerance_dt(n);
                    let worst = measure(chain, &scene, n, dt, WINDOW, false, &reference)
                        .map_or(f64::NAN, |m| m.worst);
                    format!(
                        "{set},{angle_deg},{n},{worst:.4e},{},{:.2e}",
                        reference.segments, reference.own_error
                    )
                })
                .collect();
            eprintln!(
                "{set} {angle_deg}°: reference own error {:.1e}",
                reference.own_error
            );
            Ok(lines)
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    println!("set,angle_deg,segments,worst,reference_segments,reference_own_error");
    for line in rows.into_iter().flatten() {
        println!("{line}");
    }
    Ok(())
}
