//! The release atlas: the worst tip error to t = 3 of the rods (the chain at its tolerance
//! step) from each release angle 0°, 10°, …, 90° at N = 16 … 1131, against the chain
//! extrapolated from N = 800, 1600 and 3200; and the same at the held-out angles 5°, 15°, …,
//! 85°, which measure how far an angle between two of the atlas's can stray from them.
//! `scripts/release-atlas.sh` runs it (about 20 minutes on 2 cores) and writes
//! `assets/release-atlas/atlas.csv`, which `--tolerance` reads at build time
//! (`rope::plan::atlas`).
//!
//! `release_atlas graded`: the same of the graded rods (`--method graded`) at their tolerance
//! step, against the graded rods extrapolated from N = 800, 1600 and 3200, from 20° up
//! ([`GRADED_FROM`]); `scripts/release-atlas.sh graded` writes
//! `assets/release-atlas/graded-atlas.csv`. `release_atlas graded 30,40`: those angles' rows
//! alone.
//!
//! A reference whose own error is above [`REFINED_TO`] is made from N = 1600, 3200 and 6400
//! instead. The graded rods' is doubled once more (to at most [`TWICE_REFINED`]) where it
//! keeps the atlas from trusting an entry it needs: at an atlas angle, any entry (the choices
//! read the row up to N = 1131); at a held-out angle, an entry whose neighbours the committed
//! atlas trusts and which, at its bound, would stray above them (it could set the margin).

use rayon::prelude::*;
use rope::methods::MethodKind;
use rope::model::Scene;
use rope::plan::atlas::{
    ATLAS_ANGLES, Atlas, GRADED_FROM, HELD_OUT_ANGLES, SEGMENTS, WINDOW, trusted,
};
use rope::study::tip_reference::TipReference;
use rope::study::tolerance_check::measure;

/// The reference's N: runs at N/2, N and 2N.
const REFERENCE_SEGMENTS: usize = 1600;

/// The own error a reference is refined towards, by one doubling of its N (one more run, at
/// 4N): the atlas trusts errors down to ten times its reference's own, and the graded rods
/// near N = 800 err by 4e-5 to 7e-5 (1e-4 with the atlas's margins). Where one doubling
/// does not reach it, the refined reference still lets the atlas trust smaller errors.
const REFINED_TO: f64 = 3e-6;

/// The largest N a reference is refined to (its finest run at 2N): one doubling.
const REFINED_SEGMENTS: usize = 2 * REFERENCE_SEGMENTS;

/// The largest N a reference is doubled to: its finest run at 12 800, about 1 300 s of CPU
/// (`docs/measurements.md`).
const TWICE_REFINED: usize = 2 * REFINED_SEGMENTS;

/// A reference's own error below this is round-off (the vertical release hangs still): no
/// doubling can make the atlas trust errors of that size.
const ROUND_OFF: f64 = 1e-12;

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (method, from) = match args.first().map(String::as_str) {
        None => (MethodKind::Chain, 0.0),
        Some("graded") => (MethodKind::Graded, GRADED_FROM),
        Some(other) => anyhow::bail!("usage: release_atlas [graded [ANGLES]] ({other:?} given)"),
    };
    // Only these angles, where given (to remeasure some rows).
    let only: Option<Vec<f64>> = match args.get(1) {
        Some(list) => Some(list.split(',').map(str::parse).collect::<Result<_, _>>()?),
        None => None,
    };
    let angles: Vec<(&str, f64)> = ATLAS_ANGLES
        .iter()
        .map(|&a| ("atlas", a))
        .chain(HELD_OUT_ANGLES.iter().map(|&a| ("held-out", a)))
        .filter(|&(_, a)| a >= from)
        .filter(|(_, a)| only.as_ref().is_none_or(|o| o.contains(a)))
        .collect();
    let rows = angles
        .par_iter()
        .map(|&(set, angle_deg)| {
            let scene = Scene::Release { angle_deg };
            let mut reference = TipReference::refined_by(
                method,
                &scene,
                REFERENCE_SEGMENTS,
                REFINED_SEGMENTS,
                REFINED_TO,
                WINDOW,
            )?;
            let row = |reference: &TipReference| -> Vec<(usize, f64)> {
                SEGMENTS
                    .iter()
                    .map(|&n| {
                        let dt = method.tolerance_dt(n);
                        let worst = measure(method, &scene, n, dt, WINDOW, false, reference)
                            .map_or(f64::NAN, |m| m.worst);
                        (n, worst)
                    })
                    .collect()
            };
            let mut worst = row(&reference);
            if method == MethodKind::Graded
                && reference.segments * 2 <= TWICE_REFINED
                && reference.own_error > ROUND_OFF
                && keeps_out(set, angle_deg, &worst, reference.own_error)
            {
                eprintln!(
                    "{set} {angle_deg}°: own error {:.1e} at N = {}; doubled",
                    reference.own_error, reference.segments
                );
                reference = reference.doubled()?;
                worst = row(&reference);
            }
            eprintln!(
                "{set} {angle_deg}°: reference N = {} (order {:.2}), own error {:.1e}",
                reference.segments, reference.order, reference.own_error
            );
            let lines: Vec<String> = worst
                .into_iter()
                .map(|(n, worst)| {
                    format!(
                        "{set},{angle_deg},{n},{worst:.4e},{},{:.2e}",
                        reference.segments, reference.own_error
                    )
                })
                .collect();
            Ok(lines)
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    println!("set,angle_deg,segments,worst,reference_segments,reference_own_error");
    for line in rows.into_iter().flatten() {
        println!("{line}");
    }
    Ok(())
}

/// Whether a graded row measured against a reference of own error `own` leaves out an entry
/// the atlas needs: at an atlas angle, any it does not trust; at a held-out angle, one it does
/// not trust where the committed atlas trusts both neighbours and the entry's bound (its error
/// plus `own`) is above theirs.
fn keeps_out(set: &str, angle_deg: f64, worst: &[(usize, f64)], own: f64) -> bool {
    if set == "atlas" {
        return worst.iter().any(|&(_, e)| !trusted(e, own));
    }
    let Some(neighbours) = Atlas::committed_graded().and_then(|a| a.neighbours(angle_deg)) else {
        return false;
    };
    worst
        .iter()
        .zip(neighbours)
        .any(|(&(_, e), n)| !trusted(e, own) && n.is_some_and(|n| e + own > n))
}
