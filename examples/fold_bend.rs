//! How many rods the fold's bend needs: the free end's speed against Calkin & March's,
//! the worst over x in [0.05, 0.75] and in [0.75, 0.85], for gaps d and rod counts N, with
//! `midpoint` at its default step, read at every step before the snap. The docs' d/h
//! rule and the run's warning come from this table.
//!
//! `cargo run --release --example fold_bend` (about a minute on 2 cores).

use rayon::prelude::*;
use rope::methods::MethodKind;
use rope::model::{Scene, fold};
use rope::run::simulate::{self, Options};
use std::ops::ControlFlow;

fn main() -> anyhow::Result<()> {
    let cases: Vec<(usize, f64)> = [50, 100, 200, 400]
        .iter()
        .flat_map(|&n| {
            [0.25, 0.5, 1.0, 2.0, 4.0, 8.0]
                .iter()
                .map(move |&rods| (n, rods / n as f64))
        })
        .collect();
    let rows = cases
        .par_iter()
        .map(|&(n, gap)| {
            let method = MethodKind::Midpoint;
            let dt = method.default_dt(n);
            let mut run = method.build(&Scene::Fold { gap }, n, dt)?;
            let options = Options {
                duration: 1.3,
                log_rate: 1.0 / dt,
                frame_grid: None,
            };
            let (mut start, mut highest) = (None, f64::NEG_INFINITY);
            let (mut to_075, mut to_085): (f64, f64) = (0.0, 0.0);
            simulate::run(run.as_mut(), &options, None, |f| {
                let y0 = *start.get_or_insert(f.tip().y);
                let x = f.tip().y - y0;
                if x < highest {
                    return ControlFlow::Break(()); // the snap
                }
                highest = x;
                let off = (f.tip_velocity.norm() / fold::speed(x) - 1.0).abs();
                if (0.05..=0.75).contains(&x) {
                    to_075 = to_075.max(off);
                } else if (0.75..=0.85).contains(&x) {
                    to_085 = to_085.max(off);
                }
                ControlFlow::Continue(())
            });
            Ok(format!(
                "{n},{gap},{:.2},{:.2},{:.2}",
                gap * n as f64,
                100.0 * to_075,
                100.0 * to_085
            ))
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    println!("segments,gap,rods_across_gap,speed_off_pct_to_0.75,speed_off_pct_0.75_to_0.85");
    for row in rows {
        println!("{row}");
    }
    Ok(())
}
