//! Where the fold's pilots start: how the tip's error, at every step to just before the snap,
//! and the live estimate's first-order bound fall with N, counted in rods across the gap
//! (N × gap), for `midpoint` (the fold's method) at its tolerance step. Below some sixteen rods
//! across the gap the error has not reached the order it falls at, and the estimate (the run
//! against its shadow at N/2) reads a fraction of it: `--tolerance` flies the fold's pilots
//! from N = 16 / gap (`plan::pilot::levels`).
//!
//! `cargo run --release --example fold_levels -- [GAP,GAP…] [DURATION]` (by default gaps
//! 0.02 and 0.04 to t = 1.18, just before the snap of either; 45 s on 2 cores). Past the snap
//! (`-- 0.02 1.2`) it shows what `--tolerance` does not serve.
//! Each reference is the midpoint method at N = 1 600, 3 200 and 6 400, extrapolated in N.

#[path = "common/args.rs"]
mod args;

use rope::methods::MethodKind;
use rope::model::{Scene, fold};
use rope::run::estimate::TipBound;
use rope::study::tip_reference::{ConvergedTip, TipReference};
use rope::study::tolerance_check::measure;

fn main() -> anyhow::Result<()> {
    let mut argv = std::env::args().skip(1);
    let gaps = args::numbers(argv.next(), &[0.02, 0.04])?;
    let duration = args::number(argv.next(), 1.18)?;
    let method = MethodKind::Midpoint;
    println!(
        "| gap | snap at t | N | rods across the gap | worst tip error to t = {duration} | error ratio to the N below | live estimate's first-order bound | bound / error |\n|---|---|---|---|---|---|---|---|"
    );
    for gap in gaps {
        let scene = Scene::Fold { gap };
        if duration > fold::snap_time(gap) {
            eprintln!(
                "gap {gap}: t = {duration} is past the snap, t = {:.4}, where --tolerance stops",
                fold::snap_time(gap)
            );
        }
        let reference = TipReference::compute_by(method, &scene, 3200, duration)?;
        eprintln!(
            "gap {gap}: reference of N = 1600, 3200, 6400, order {:.2}, own error {:.1e} at every 1/3000",
            reference.order,
            reference.own_error_over(duration, 3000.0)
        );
        let mut below: Option<f64> = None;
        for rods in [2.0, 4.0, 8.0, 16.0, 32.0] {
            let segments = (rods / gap).round() as usize;
            let dt = method.tolerance_dt(segments);
            let measured = measure(
                method,
                &scene,
                segments,
                dt,
                duration,
                Some(TipBound::FirstOrder),
                &reference,
            )
            .ok_or_else(|| anyhow::anyhow!("the run at N = {segments} did not finish"))?;
            let bound = measured.estimate.unwrap_or(f64::NAN);
            let ratio = below.map_or("–".to_owned(), |b| format!("{:.2}", b / measured.worst));
            println!(
                "| {gap} | {:.4} | {segments} | {rods} | {:.2e} | {ratio} | {bound:.2e} | {:.2} |",
                fold::snap_time(gap),
                measured.worst,
                bound / measured.worst
            );
            below = Some(measured.worst);
        }
    }
    Ok(())
}
