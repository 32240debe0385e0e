//! A fixed workload of steps for counting instructions: METHOD at N rods from 30°, at its
//! default step, stepped STEPS times, nothing else (no frames, no estimate). On a machine
//! whose speed drifts by a fifth within minutes, the instructions of two builds compare where
//! their timings cannot:
//!
//! `valgrind --tool=callgrind target/release/examples/steps_alone midpoint 1000 300`
//! (by default the midpoint rule at N = 1 000, 300 steps; prints the time reached).

#[path = "common/args.rs"]
mod args;

use rope::model::Scene;

fn main() -> anyhow::Result<()> {
    let mut given = std::env::args().skip(1);
    let method = args::method(given.next())?;
    let segments = args::number(given.next(), 1000.0)?;
    let steps = args::number(given.next(), 300.0)?;
    anyhow::ensure!(
        segments >= 1.0 && segments.fract() == 0.0 && steps >= 0.0 && steps.fract() == 0.0,
        "N and STEPS are whole numbers, N at least 1 (given {segments} and {steps})"
    );
    let segments = segments as usize;
    let scene = Scene::Release { angle_deg: 30.0 };
    let mut rope = method.build(&scene, segments, method.default_dt(segments))?;
    for _ in 0..steps as u64 {
        rope.step()?;
    }
    println!("{method} at N = {segments}: t = {}", rope.time());
    Ok(())
}
