//! The graded rods (`--method graded`) as scenarios: drawn at their own lengths, their
//! tensions where they act, their tip moving as its velocity says, and the string they reach
//! the equal rods' own.

use rope::methods::MethodKind;
use rope::model::Scene;
use rope::model::geometry::Point;
use rope::run::simulate::{self, Frame, Options};
use std::ops::ControlFlow;

const THIRTY: Scene = Scene::Release { angle_deg: 30.0 };

/// Every frame of `method` at N = `segments` and its default step over `finer` from `scene`
/// to `duration`, at `rate` a unit.
fn frames(
    method: MethodKind,
    scene: &Scene,
    segments: usize,
    finer: f64,
    duration: f64,
    rate: f64,
) -> Vec<Frame> {
    let dt = method.default_dt(segments) / finer;
    let mut run = method.build(scene, segments, dt).unwrap();
    let options = Options {
        duration,
        log_rate: rate,
        frame_grid: None,
    };
    let mut kept = Vec::new();
    let outcome = simulate::run(run.as_mut(), &options, None, |f| {
        kept.push(f);
        ControlFlow::Continue(())
    });
    assert!(outcome.diverged.is_none(), "{:?}", outcome.diverged);
    kept
}

#[test]
fn a_graded_run_draws_each_rod_at_its_own_length_shorter_towards_the_tip() {
    let n = 40;
    let kept = frames(MethodKind::Graded, &THIRTY, n, 1.0, 2.0, 30.0);
    for f in &kept {
        let edges = f
            .edges
            .as_ref()
            .expect("graded rods carry their arc lengths");
        assert_eq!(edges.len(), n + 1);
        assert!(
            edges[0] == 0.0 && (edges[n] - 1.0).abs() < 1e-12,
            "{edges:?}"
        );
        for i in 0..n {
            // Rigid rods: each node is its rod's length from the last, s_i = 1 − (1 − i/N)^1.5.
            let length = edges[i + 1] - edges[i];
            let expected =
                (1.0 - i as f64 / n as f64).powf(1.5) - (1.0 - (i + 1) as f64 / n as f64).powf(1.5);
            assert!(
                (length - expected).abs() < 1e-12,
                "rod {i}: {length} against {expected}"
            );
            let drawn = (f.nodes[i + 1] - f.nodes[i]).norm();
            assert!((drawn - length).abs() < 1e-12, "t = {}, rod {i}", f.time);
        }
        // The first rod is about 1.5/N long, the last about 1.5 N^-1.5: twelve times shorter.
        assert!(edges[1] - edges[0] > 6.0 * (edges[n] - edges[n - 1]));
    }
}

#[test]
fn the_graded_tip_moves_as_its_velocity_says() {
    // Frames 1/20000 apart: the central difference of the tip's positions against the
    // velocity the frame carries (Σ l_i φ̇_i n_i), through the fall and the whip (where the
    // tip's velocity turns through a radian in 0.002).
    let kept = frames(MethodKind::Graded, &THIRTY, 60, 20.0, 1.6, 20000.0);
    let mut worst: f64 = 0.0;
    for w in kept.windows(3) {
        let span = w[2].time - w[0].time;
        let difference = (w[2].tip() - w[0].tip()) / span;
        let speed = w[1].tip_velocity.norm().max(1.0);
        worst = worst.max((difference - w[1].tip_velocity).norm() / speed);
    }
    assert!(worst < 1e-3, "{worst:e}");
}

#[test]
fn graded_rods_and_equal_rods_reach_the_same_string() {
    // At t = 1 from 30°, before the whip: the graded rods at N = 100 and the chain at
    // N = 400, shape compared at equal arc length and tension at the support.
    let graded = frames(MethodKind::Graded, &THIRTY, 100, 1.0, 1.0, 10.0);
    let equal = frames(MethodKind::Chain, &THIRTY, 400, 1.0, 1.0, 10.0);
    let (g, e) = (graded.last().unwrap(), equal.last().unwrap());
    assert!((g.time - 1.0).abs() < 1e-9 && (e.time - 1.0).abs() < 1e-9);
    let apart = rope::model::geometry::largest_distance_of(
        &g.nodes,
        g.edges.as_deref(),
        &e.nodes,
        e.edges.as_deref(),
    );
    assert!(apart < 2e-3, "{apart:e}");
    assert!((g.support_tension - e.support_tension).abs() < 1e-2);
    let tip: Point = g.tip();
    assert!((tip - e.tip()).norm() < 2e-3, "{tip:?} {:?}", e.tip());
}
