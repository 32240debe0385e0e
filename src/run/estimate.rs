//! The live error estimate: a shadow of the run at half the segments and twice the time step,
//! stepped alongside it, and Richardson's estimate of the main run's error from the two.
//!
//! With the error ≈ C h^p, the run at N has error e and its shadow at M = N/2 has about
//! r^p e (r = N/M), so e ≈ |x_N − x_M| / (r^p − 1). The shadow doubles the step too, so a
//! method whose error in k has the same order as in h (the report's scheme, `rattle`) scales
//! as a whole; for the RK4 chain the error in k is negligible.

use super::shadow_steps::ShadowSteps;
use crate::error::{ConfigError, Diverged};
use crate::methods::MethodKind;
use crate::model::Scene;
use crate::model::geometry::{self, Point};

/// Main steps per shadow step: the shadow's step is this many times the run's.
pub const STRIDE: u64 = 2;

/// How the live estimate bounds the tip's error, what `--tolerance` is held to.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum TipBound {
    /// Richardson's estimate at first order, |x_N − x_(N/2)| / (r − 1): the lowest order any
    /// method shows (a whip's; through the whip, from 20° to 80°, the estimate at the nominal
    /// order read 0.42 to 1.0 of the true error: `examples/tolerance_instants.rs`,
    /// `assets/tolerance-instants/`). The default, and a release's, a fold's and a shake's.
    #[default]
    FirstOrder,
    /// Richardson's estimate at an order measured on the scene itself (by `--tolerance`'s pilots,
    /// or worked out by a mode's linear theory, `plan::mode_theory`), times `safety` (at least 1), where that is below the first-order bound: for a scene with no
    /// whip, whose error keeps the order the pilots saw (a mode's). At first order there the bound
    /// reads about three times a second-order error, and a run whose truth is a third of its
    /// tolerance would be flagged.
    Observed { order: f64, safety: f64 },
}

impl TipBound {
    /// What |x_N − x_M| is multiplied by for the bound, with r = N / M.
    fn factor(self, ratio: f64) -> f64 {
        let first = 1.0 / (ratio - 1.0);
        match self {
            Self::FirstOrder => first,
            // A safety below 1 would bound less than the estimate: taken as 1.
            Self::Observed { order, safety } => {
                first.min(safety.max(1.0) / (ratio.powf(order) - 1.0))
            }
        }
    }

    /// The bound over the first-order bound (at most 1), with r = N / M.
    pub fn of_first_order(self, ratio: f64) -> f64 {
        self.factor(ratio) * (ratio - 1.0)
    }

    /// The bound's name in a sentence ("the tip error's first-order bound").
    pub fn name(self) -> String {
        match self {
            Self::FirstOrder => "first-order bound".to_owned(),
            Self::Observed { order, safety } => {
                format!(
                    "bound at the mode's own order ({order:.2}, seen by its pilots or worked out by the linear theory, ×{safety} safety)"
                )
            }
        }
    }

    /// How far below the bound the truth may be, where the error has the order it assumes or
    /// a higher one (in a sentence: "the truth may be anywhere above …").
    pub fn truth_from(self) -> String {
        match self {
            Self::FirstOrder => "about a third of the bound".to_owned(),
            Self::Observed { safety, .. } => {
                format!("about {:.0} % of the bound", 100.0 / safety.max(1.0))
            }
        }
    }
}

/// Richardson's estimate of the run's error at one instant, in string lengths.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct ErrorEstimate {
    /// Of the tip's position.
    pub tip: f64,
    /// Of the shape: the largest distance between the two strings at the shadow's nodes.
    pub shape: f64,
}

/// The tip's live estimate at one step, and the bound the tolerance is held to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TipEstimate {
    /// Richardson's estimate at the method's nominal order.
    pub estimate: f64,
    /// The bound the run's [`TipBound`] makes of it: what `--tolerance` is watched by.
    pub bound: f64,
}

/// The run at half its segments, kept in step with it.
pub struct Shadow {
    /// The shadow's states, stepped on the run's thread or ahead on its own.
    steps: ShadowSteps,
    /// 1 / (r^p − 1), r = N / M, p the method's order in h.
    richardson: f64,
    /// What |x_N − x_M| is multiplied by for the tip's bound ([`TipBound`]).
    bound_factor: f64,
    /// Why the shadow stopped, if it did: the estimates end there.
    lost: Option<Diverged>,
    nodes: Vec<Point>,
    /// The shadow's nodes' arc lengths (fixed: its rods keep their lengths).
    edges: Vec<f64>,
}

impl Shadow {
    /// The shadow's segment count for a run of `segments`.
    pub fn segments_of(segments: usize) -> usize {
        segments / 2
    }

    /// Whether a run of `method` at `segments` can have a shadow: half its segments must be
    /// enough for the method.
    pub fn possible(method: MethodKind, segments: usize) -> bool {
        Self::segments_of(segments) >= method.descriptor().min_segments
    }

    /// The shadow of a run of `method` in `scene` at `segments` and step `dt`, bounding the
    /// tip's error as `bound` says; `None` where the run is too coarse to have one
    /// ([`Shadow::possible`]).
    pub fn new(
        method: MethodKind,
        scene: &Scene,
        segments: usize,
        dt: f64,
        bound: TipBound,
    ) -> Result<Option<Self>, ConfigError> {
        if !Self::possible(method, segments) {
            return Ok(None);
        }
        let half = Self::segments_of(segments);
        let shadow = method.build(scene, half, dt * STRIDE as f64)?;
        let ratio = segments as f64 / half as f64;
        let order = method.descriptor().order_in_h;
        // Its rods' lengths never change, nor therefore where its nodes sit along it.
        let mut edges = Vec::with_capacity(half + 1);
        geometry::edges(half, shadow.lengths(), &mut edges);
        Ok(Some(Self {
            steps: ShadowSteps::here(shadow),
            richardson: 1.0 / (ratio.powi(order as i32) - 1.0),
            bound_factor: bound.factor(ratio),
            lost: None,
            nodes: Vec::with_capacity(half + 1),
            edges,
        }))
    }

    /// Why the shadow stopped, if it has: no estimate comes after.
    pub fn lost(&self) -> Option<&Diverged> {
        self.lost.as_ref()
    }

    /// Brings the shadow to the run's step `step` and estimates the error of the run's
    /// `nodes` (support … tip; at arc lengths `edges`, `None` for equal segments). `None` if
    /// `step` is not a multiple of [`STRIDE`] (the two are not at the same instant) or the
    /// shadow has stopped.
    pub fn estimate(
        &mut self,
        step: u64,
        nodes: &[Point],
        edges: Option<&[f64]>,
    ) -> Option<ErrorEstimate> {
        if !self.advance_to(step) {
            return None;
        }
        // In the room, as the run's nodes are.
        self.steps.nodes(&mut self.nodes);
        let tip = nodes.last().copied().unwrap_or_else(Point::origin);
        let shadow_tip = self.nodes.last().copied().unwrap_or_else(Point::origin);
        let shape = geometry::largest_distance_at(&self.nodes, &self.edges, nodes, edges);
        Some(ErrorEstimate {
            tip: (tip - shadow_tip).norm() * self.richardson,
            shape: shape * self.richardson,
        })
    }

    /// Brings the shadow to the run's step `step` and estimates the error of the run's `tip`
    /// there (in the room), at every step the two share, frames or none. `None` as for
    /// [`Shadow::estimate`].
    pub fn tip_estimate(&mut self, step: u64, tip: Point) -> Option<TipEstimate> {
        if !self.advance_to(step) {
            return None;
        }
        let shadow_tip = self.steps.tip();
        let gap = (tip - shadow_tip).norm();
        Some(TipEstimate {
            estimate: gap * self.richardson,
            bound: gap * self.bound_factor,
        })
    }

    /// Steps the shadow to the instant of the run's step `step`; false if the two share no
    /// instant there (`step` not a multiple of [`STRIDE`]) or the shadow has stopped (its
    /// energy grew without bound, or a step failed).
    fn advance_to(&mut self, step: u64) -> bool {
        if self.lost.is_some() || !step.is_multiple_of(STRIDE) {
            return false;
        }
        match self.steps.advance_to(step / STRIDE) {
            Ok(()) => true,
            Err(why) => {
                self.lost = Some(why);
                false
            }
        }
    }

    /// The same shadow, stepped ahead of the run on a core of its own (the same states, bit
    /// for bit: the shadow never reads the run).
    pub fn ahead(self) -> Self {
        Self {
            steps: self.steps.ahead(),
            ..self
        }
    }

    /// CPU seconds a thread of its own has spent on the shadow: none where it is stepped on
    /// the run's thread, which counts them.
    pub fn own_thread_seconds(&self) -> f64 {
        self.steps.own_thread_seconds()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::run::shadow_steps::BATCH;

    /// Two shadows of a run of `method` at N = 40 and step `dt` in `scene`, one stepped on the
    /// run's thread and one ahead on its own, and the run's tip at the start.
    fn here_and_ahead(method: MethodKind, scene: &Scene, dt: f64) -> (Shadow, Shadow, Point) {
        let make = || {
            Shadow::new(method, scene, 40, dt, TipBound::FirstOrder)
                .unwrap()
                .unwrap()
        };
        let mut nodes = Vec::new();
        geometry::nodes(&scene.initial_angles(40), &mut nodes);
        (make(), make().ahead(), *nodes.last().unwrap())
    }

    /// A step at which the shadow of the report's scheme at N = 20 (twice this step) blows
    /// up, some hundreds of its steps in.
    const DIVERGING_DT: f64 = 0.01;

    #[test]
    fn a_run_too_coarse_to_halve_has_no_shadow() {
        let scene = Scene::Release { angle_deg: 30.0 };
        assert!(
            Shadow::new(MethodKind::Seed, &scene, 7, 1e-3, TipBound::FirstOrder)
                .unwrap()
                .is_none()
        );
        assert!(
            Shadow::new(MethodKind::Seed, &scene, 8, 1e-3, TipBound::FirstOrder)
                .unwrap()
                .is_some()
        );
    }

    #[test]
    fn at_the_start_the_run_and_its_shadow_agree() {
        let scene = Scene::Release { angle_deg: 30.0 };
        let mut shadow = Shadow::new(MethodKind::Chain, &scene, 10, 1e-3, TipBound::FirstOrder)
            .unwrap()
            .unwrap();
        let mut nodes = Vec::new();
        geometry::nodes(&scene.initial_angles(10), &mut nodes);
        let e = shadow.estimate(0, &nodes, None).unwrap();
        assert!(e.tip < 1e-15 && e.shape < 1e-15);
        assert!(shadow.estimate(1, &nodes, None).is_none());
    }

    #[test]
    fn a_shadow_that_diverges_ahead_stops_where_one_stepped_here_does() {
        // The report's scheme past its stability limit blows up some batches in: the thread
        // ahead ends its batch at the divergence, and the run reads it at the same shared
        // step as a shadow stepped on the run's thread, for the same reason, every estimate
        // before it the same.
        let scene = Scene::Release { angle_deg: 30.0 };
        let (mut here, mut ahead, tip) = here_and_ahead(MethodKind::Seed, &scene, DIVERGING_DT);
        let lost_at = (0..100_000)
            .step_by(STRIDE as usize)
            .find(|&step| {
                let (a, b) = (here.tip_estimate(step, tip), ahead.tip_estimate(step, tip));
                assert_eq!(a, b, "step {step}");
                a.is_none()
            })
            .expect("the shadow diverged");
        let (a, b) = (here.lost().unwrap(), ahead.lost().unwrap());
        assert_eq!((a.step, &a.reason), (b.step, &b.reason));
        // Past the first batches, not at the start.
        assert!(
            lost_at > 4 * BATCH as u64 * STRIDE,
            "lost at step {lost_at}"
        );
        assert!(a.reason.contains("grew without bound"), "{}", a.reason);
    }

    #[test]
    fn a_shadow_stepped_ahead_on_its_own_thread_estimates_the_same_bit_for_bit() {
        // The run's tip and nodes stand still at the start; the shadow swings away from them,
        // and both shadows must say the same of it at every shared step: through a whip, on
        // graded rods (whose nodes the run draws from the angles sent ahead, with the rods'
        // lengths), and under a shaken support (the nodes carried into the room).
        let shaken = Scene::Shake {
            amplitude: 0.05,
            frequency: 2.0,
            start: crate::model::ShakeStart::Rest,
        };
        // Each with how far its shadow has swung from the still tip by step 1 500 at least.
        let cases = [
            (
                MethodKind::Midpoint,
                Scene::Release { angle_deg: 0.0 },
                2e-3,
                0.1,
            ),
            (
                MethodKind::Graded,
                Scene::Release { angle_deg: 30.0 },
                1e-3,
                0.1,
            ),
            (MethodKind::Chain, shaken, 2e-3, 1e-3),
        ];
        for (method, scene, dt, swung) in cases {
            let (mut here, mut ahead, tip) = here_and_ahead(method, &scene, dt);
            let mut nodes = Vec::new();
            geometry::nodes(&scene.initial_angles(40), &mut nodes);
            for step in (0..1_500).step_by(STRIDE as usize) {
                let (a, b) = (here.tip_estimate(step, tip), ahead.tip_estimate(step, tip));
                assert_eq!(a, b, "{method}, step {step}");
                if step % 100 == 0 {
                    let (a, b) = (
                        here.estimate(step, &nodes, None),
                        ahead.estimate(step, &nodes, None),
                    );
                    assert_eq!(a, b, "{method}, step {step}");
                }
            }
            let far = here.tip_estimate(1_500, tip).unwrap().estimate;
            assert!(far > swung, "{method}: swung {far:e}");
            assert_eq!(here.own_thread_seconds(), 0.0);
            assert!(ahead.own_thread_seconds() > 0.0);
        }
    }
}
