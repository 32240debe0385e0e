//! rope as a library, without Rerun: the chain released from the horizontal, its free end's
//! fall against free fall's t²/2 (exact until the bend reaches the tip, near t = 1.2), and
//! the tension at the support. Builds with `default-features = false`:
//!
//! ```text
//! cargo run --release --no-default-features --example library
//! ```

use rope::{MethodKind, RunConfig, Scene};

fn main() -> Result<(), rope::ConfigError> {
    let run = rope::simulate(&RunConfig {
        method: MethodKind::Chain,
        scene: Scene::Release { angle_deg: 0.0 },
        segments: 200,
        duration: 1.5,
        log_rate: 10.0,
        ..RunConfig::default()
    })?;
    println!("t,tip_x,tip_y,free_fall_y,support_tension,energy");
    for frame in &run.frames {
        let tip = frame.tip();
        let (t, energy) = (frame.time, frame.energy.total());
        let free_fall = t * t / 2.0;
        let pull = frame.support_tension;
        println!(
            "{t:.2},{:.6},{:.6},{free_fall:.6},{pull:.4},{energy:.6}",
            tip.x, tip.y
        );
    }
    let summary = &run.summary;
    eprintln!(
        "{} steps; energy kept to {:.1e} of |E|; largest pull at the support {:.3} at t = {:.3}",
        summary.steps,
        summary.energy.max_rel_deviation,
        summary.max_support_tension,
        summary.max_support_tension_time
    );
    Ok(())
}
