//! The midpoint rule's tip at every step (or every few), for the examples that measure what
//! its default step costs the tip in time.

use rope::methods::{Method, MethodKind};
use rope::model::Scene;
use rope::model::geometry::Point;
use rope::model::support::tip_in_the_room;

/// The tip at every `every`-th step to `duration`, and the run's CPU seconds (its thread's).
pub fn tips(scene: &Scene, n: usize, dt: f64, every: u64, duration: f64) -> (Vec<Point>, f64) {
    let cpu = cpu_time::ThreadTime::now();
    let mut method = MethodKind::Midpoint
        .build(scene, n, dt)
        .expect("midpoint starts from every release");
    let total = (duration / dt).round() as u64;
    let tip = |m: &dyn Method| tip_in_the_room(m.support(), m.angles(), m.lengths());
    let mut out = vec![tip(method.as_ref())];
    while method.steps() < total {
        method.step().expect("midpoint does not diverge");
        if method.steps().is_multiple_of(every) {
            out.push(tip(method.as_ref()));
        }
    }
    (out, cpu.elapsed().as_secs_f64())
}

/// The largest distance between two runs' tips, sampled at the same instants.
pub fn largest(a: &[Point], b: &[Point]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| (p - q).norm())
        .fold(0.0, f64::max)
}

/// Every (release angle, N) pair, angle by angle: the cells of a table.
pub fn cells(angles: &[f64], segments: &[usize]) -> Vec<(f64, usize)> {
    angles
        .iter()
        .flat_map(|&a| segments.iter().map(move |&n| (a, n)))
        .collect()
}
