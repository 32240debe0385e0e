//! A run's tip at every one of its steps, to be read at any time: what a study's errors are
//! measured against at every frame.

use super::progress::Progress;
use super::run_cache;
use crate::error::Diverged;
use crate::methods::chain::Chain;
use crate::methods::{Method, MethodKind};
use crate::model::Scene;
use crate::model::geometry::{self, Point};

/// How many steps a kept run takes between asking whether it should stop: a long reference
/// (minutes at N = 12 800) ends within a fraction of a second of a Ctrl-C.
const STOP_EVERY: usize = 256;

/// The tip at every step of a run of constant step `dt`, from t = 0.
#[derive(Clone, Debug, PartialEq)]
pub struct Trajectory {
    dt: f64,
    tips: Vec<Point>,
}

/// A run kept at every step: its tip throughout, and its final state.
pub struct Kept {
    pub trajectory: Trajectory,
    /// The tip at the final time (the step nearest `duration`, where a run ends).
    pub tip: Point,
    /// The segment angles there.
    pub angles: Vec<f64>,
}

/// The frame times of a run of `duration` at `rate` frames a time unit: 0, 1/rate, … to the
/// frame nearest `duration`.
pub fn frame_times(duration: f64, rate: f64) -> Vec<f64> {
    let frames = (duration * rate).round() as usize;
    (0..=frames).map(|j| j as f64 / rate).collect()
}

impl Trajectory {
    /// The tips `tips`, one every `dt` from t = 0.
    pub fn new(dt: f64, tips: Vec<Point>) -> Self {
        Self { dt, tips }
    }

    /// [`MethodKind::REFERENCE`] at `segments` and its default step, from `scene` to
    /// `duration`.
    pub fn compute(scene: &Scene, segments: usize, duration: f64) -> anyhow::Result<Self> {
        Self::compute_by(MethodKind::REFERENCE, scene, segments, duration, &|| ())
    }

    /// `method` at `segments` and its default step, from `scene` to `duration`; read back
    /// instead where a folder of kept runs holds it, and kept there once run
    /// ([`super::run_cache`]). `progress` may stop the run partway
    /// ([`Stopped`](super::Stopped)); nothing is kept then.
    pub fn compute_by(
        method: MethodKind,
        scene: &Scene,
        segments: usize,
        duration: f64,
        progress: &impl Progress,
    ) -> anyhow::Result<Self> {
        let dt = method.default_dt(segments);
        let kept = run_cache::Kept::of(method, scene, segments, dt, duration);
        let (dt, tips) = run_cache::computed_or_kept(kept, || {
            let run =
                Self::keep_stoppable(scene, method, segments, dt, duration, progress)?.trajectory;
            Ok((run.dt, run.tips))
        })?;
        Ok(Self::new(dt, tips))
    }

    /// As [`Trajectory::compute`], on `segments` rods graded towards the free end with
    /// `exponent` ([`Chain::graded`]; 1: equal rods, [`Trajectory::compute`]), at the equal
    /// rods' default step (the substeps follow each rod's own wave and spin).
    pub fn compute_graded(
        scene: &Scene,
        segments: usize,
        duration: f64,
        exponent: f64,
    ) -> anyhow::Result<Self> {
        if exponent == 1.0 {
            return Self::compute(scene, segments, duration);
        }
        let dt = MethodKind::Chain.default_dt(segments);
        let descriptor = MethodKind::Graded.descriptor();
        let mut chain = Chain::graded(descriptor, scene, segments, dt, exponent)?;
        let (tips, _) = Self::tips_of(&mut chain, dt, duration, &(|| ()), |d| {
            anyhow::anyhow!("graded chain at N = {segments}: {d}")
        })?;
        Ok(Self::new(dt, tips))
    }

    /// `method` at `segments` and step `dt` from `scene`, kept at every step to two steps
    /// past `duration` (so that the cubic of [`Trajectory::at`] has its four points there),
    /// with its state at the step a run to `duration` ends on.
    pub fn keep(
        scene: &Scene,
        method: MethodKind,
        segments: usize,
        dt: f64,
        duration: f64,
    ) -> anyhow::Result<Kept> {
        Self::keep_stoppable(scene, method, segments, dt, duration, &(|| ()))
    }

    /// As [`Trajectory::keep`], ended partway ([`Stopped`](super::Stopped)) once `progress`
    /// asks a stop.
    pub fn keep_stoppable(
        scene: &Scene,
        method: MethodKind,
        segments: usize,
        dt: f64,
        duration: f64,
        progress: &impl Progress,
    ) -> anyhow::Result<Kept> {
        let mut run = method.build(scene, segments, dt)?;
        let (tips, angles) = Self::tips_of(run.as_mut(), dt, duration, progress, |d| {
            anyhow::anyhow!(
                "the run of the {method} method at N = {segments}, k = {dt:e} from the {scene} failed: {d}"
            )
        })?;
        let last = (duration / dt).round() as usize;
        Ok(Kept {
            tip: tips[last],
            angles,
            trajectory: Self { dt, tips },
        })
    }

    /// `run`'s tip (of its rods' own lengths) at every step of `dt` to two past `duration`,
    /// and its angles at the step a run to `duration` ends on; a step that fails ends it with
    /// `failed`'s error, and `progress` asking a stop (heard every [`STOP_EVERY`] steps) with
    /// [`Stopped`](super::Stopped).
    fn tips_of(
        run: &mut dyn Method,
        dt: f64,
        duration: f64,
        progress: &impl Progress,
        failed: impl Fn(Diverged) -> anyhow::Error,
    ) -> anyhow::Result<(Vec<Point>, Vec<f64>)> {
        let lengths = run.lengths().map(<[f64]>::to_vec);
        let tip = |angles: &[f64]| geometry::tip_of(angles, lengths.as_deref());
        let last = (duration / dt).round() as usize;
        let mut tips = Vec::with_capacity(last + 3);
        tips.push(tip(run.angles()));
        let mut end = None;
        for step in 1..=last + 2 {
            if step - 1 == last {
                end = Some(run.angles().to_vec());
            }
            run.step().map_err(&failed)?;
            tips.push(tip(run.angles()));
            if step % STOP_EVERY == 0 {
                progress.check()?;
            }
        }
        let angles = end.unwrap_or_else(|| run.angles().to_vec());
        Ok((tips, angles))
    }

    /// The step between kept tips.
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// The kept tips, one a step from t = 0.
    pub fn tips(&self) -> &[Point] {
        &self.tips
    }

    /// The largest distance between this path's tip and `other`'s at `times`.
    pub fn largest_gap(&self, other: &Self, times: &[f64]) -> f64 {
        times
            .iter()
            .map(|&t| (self.at(t) - other.at(t)).norm())
            .fold(0.0, f64::max)
    }

    /// The tip at time `t`: the cubic through the four nearest steps (its error, of order
    /// k⁴, is far below the reference's own).
    pub fn at(&self, t: f64) -> Point {
        let x = t / self.dt;
        let last = self.tips.len().saturating_sub(1);
        let i = (x.floor() as usize).clamp(1, last.saturating_sub(2).max(1));
        let u = x - i as f64; // in [0, 1) inside the bracket [i, i + 1]
        let p = |j: usize| self.tips[j.min(last)].coords;
        let (a, b, c, d) = (p(i - 1), p(i), p(i + 1), p(i + 2));
        // Lagrange weights at nodes −1, 0, 1, 2.
        let wa = -u * (u - 1.0) * (u - 2.0) / 6.0;
        let wb = (u + 1.0) * (u - 1.0) * (u - 2.0) / 2.0;
        let wc = -(u + 1.0) * u * (u - 2.0) / 2.0;
        let wd = (u + 1.0) * u * (u - 1.0) / 6.0;
        Point::from(a * wa + b * wb + c * wc + d * wd)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cubic_path_is_read_exactly_between_its_steps() {
        let path = |t: f64| Point::new(t * t * t - 2.0 * t, 0.5 * t * t + 1.0);
        let dt = 0.1;
        let kept = Trajectory::new(dt, (0..=30).map(|i| path(i as f64 * dt)).collect());
        for t in [0.0, 0.05, 0.1234, 1.5, 2.77, 2.95] {
            assert!((kept.at(t) - path(t)).norm() < 1e-12, "t = {t}");
        }
    }
}
