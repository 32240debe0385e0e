//! The converged tip of a scene that `rope study --tolerance-check` and the release atlas
//! judge runs against: a method's runs at N/2, N and 2N, extrapolated in N at the order they
//! show, with its own error measured at every 1/3 000 of a time unit, and written out for
//! anyone to hold another solver against (`references.csv`); and [`ConvergedTip`], what a
//! run is measured against, computed here or read back from such a file
//! ([`read_reference`](super::read_reference)).

use super::progress::Progress;
use super::trajectory::{Trajectory, frame_times};
use crate::methods::MethodKind;
use crate::model::{Point, Scene};
use rayon::prelude::*;

/// Frames per time unit at which a run's tip is compared with the reference: a run's frames,
/// where a reference's own error is first measured.
pub const LOG_RATE: f64 = 60.0;

/// Instants per time unit at which a run's tip is judged against a reference, and a
/// reference's own error measured: every row of a references file
/// ([`REFERENCE_ROWS_RATE`]), so that a whip's error peak, narrower than a frame, is seen
/// (from 40° at 1e-3 a run's frames at 60 a unit read 8.2e-4 where its peak is 1.68e-3).
pub const JUDGE_RATE: f64 = REFERENCE_ROWS_RATE;

/// A scene's converged tip, as a run is measured against it: at any instant, with the own
/// error the reference has there.
pub trait ConvergedTip {
    /// The scene it is the converged tip of.
    fn scene(&self) -> Scene;

    /// The tip at time `t`.
    fn tip_at(&self, t: f64) -> Point;

    /// How far [`ConvergedTip::tip_at`] may be from the truth at `t`, as measured.
    fn own_error_at(&self, t: f64) -> f64;

    /// Whether it is known only at its rows (a references file, every 1/[`JUDGE_RATE`]): a
    /// run is then judged there, at a step that falls on them. Otherwise it is read at any
    /// instant (its runs' steps are far finer than a judged run's), and a run is judged at
    /// every one of its own steps.
    fn rows_only(&self) -> bool {
        false
    }

    /// The tip's largest distance from this reference over a run's `frames` after t = 0.
    fn farthest(&self, frames: &[crate::run::Frame]) -> f64 {
        frames
            .iter()
            .filter(|f| f.time > 0.0)
            .map(|f| (f.tip() - self.tip_at(f.time)).norm())
            .fold(0.0, f64::max)
    }

    /// The largest own error at `rate` instants a time unit to `duration`: at the frames
    /// ([`LOG_RATE`]) what judges a run's frames; finer, it also sees between them (a whip's
    /// peak is brief).
    fn own_error_over(&self, duration: f64, rate: f64) -> f64 {
        frame_times(duration, rate)
            .into_iter()
            .map(|t| self.own_error_at(t))
            .fold(0.0, f64::max)
    }
}

/// The converged tip of one scene: the reference method at N and 2N, extrapolated in N at the
/// order that the runs at N/2, N and 2N show.
#[derive(Clone, Debug)]
pub struct TipReference {
    /// The scene it is the reference of.
    pub scene: Scene,
    /// The method whose runs make it.
    pub method: MethodKind,
    half: Trajectory,
    coarse: Trajectory,
    fine: Trajectory,
    /// N: the reference is made of the runs at N/2, N and 2N.
    pub segments: usize,
    /// The order observed from the three, between 1 (a whip) and 2 (the chain's nominal).
    pub order: f64,
    /// The simulated time its runs cover.
    pub duration: f64,
    /// The largest change of the extrapolated tip at every 1/[`JUDGE_RATE`] of a time unit
    /// when it is made from N and 2N rather than from N/2 and N: a bound on the coarser one's
    /// error, taken for this one's (conservative where the extrapolation converges).
    pub own_error: f64,
}

impl TipReference {
    /// The reference from the runs at N/2, N and 2N (computed in parallel).
    pub fn compute(scene: &Scene, segments: usize, duration: f64) -> anyhow::Result<Self> {
        Self::compute_by(MethodKind::REFERENCE, scene, segments, duration)
    }

    /// As [`TipReference::compute`], of `method`'s runs at their default steps (the graded
    /// rods', whose tip converges faster through the whip).
    pub fn compute_by(
        method: MethodKind,
        scene: &Scene,
        segments: usize,
        duration: f64,
    ) -> anyhow::Result<Self> {
        Self::refined_by(method, scene, segments, segments, 0.0, duration, &|| ())
    }

    /// The reference of `method`'s runs from N = `segments` (with N/2 and 2N), N then doubled
    /// while its own error is above `target` and N is below `most`: each doubling one more
    /// run, at 2N. `progress` may stop its runs partway ([`Stopped`](super::Stopped)).
    pub fn refined_by(
        method: MethodKind,
        scene: &Scene,
        segments: usize,
        most: usize,
        target: f64,
        duration: f64,
        progress: &impl Progress,
    ) -> anyhow::Result<Self> {
        let compute = |n| Trajectory::compute_by(method, scene, n, duration, progress);
        let runs = [segments / 2, segments, 2 * segments]
            .into_par_iter()
            .map(compute)
            .collect::<anyhow::Result<Vec<_>>>()?;
        let [half, coarse, fine]: [Trajectory; 3] = runs
            .try_into()
            .map_err(|_| anyhow::anyhow!("three reference runs expected"))?;
        Self::of(method, *scene, half, coarse, fine, segments, duration).doubled_while(
            target,
            most,
            |_| true,
            progress,
        )
    }

    /// This reference, N doubled on while its own error is above `target`, N is below `most`
    /// and the doubling [`could_reach`](TipReference::could_reach) `target` by `most`.
    /// `progress` may stop its runs partway ([`Stopped`](super::Stopped)).
    pub fn refined_where_reachable(
        self,
        target: f64,
        most: usize,
        progress: &impl Progress,
    ) -> anyhow::Result<Self> {
        self.doubled_while(target, most, |r| r.could_reach(target, most), progress)
    }

    /// This reference, N doubled while its own error is above `target`, 2N is at most `most`
    /// and `worth` says the next doubling may pay.
    fn doubled_while(
        self,
        target: f64,
        most: usize,
        worth: impl Fn(&Self) -> bool,
        progress: &impl Progress,
    ) -> anyhow::Result<Self> {
        let mut reference = self;
        while reference.own_error > target && 2 * reference.segments <= most && worth(&reference) {
            reference = reference.doubled(progress)?;
        }
        Ok(reference)
    }

    /// Whether doubling N up to `most` could bring the own error to `target`, were it to fall
    /// at the order the runs show, or at second order if that is faster (the chain's nominal
    /// order; a whip's is first): a bound on what doubling can buy, so that a doubling that
    /// cannot reach its target is not paid for.
    pub fn could_reach(&self, target: f64, most: usize) -> bool {
        let order = match self.order.is_finite() {
            true => self.order.max(2.0),
            false => 2.0,
        };
        self.own_error * (self.segments as f64 / most as f64).powf(order) <= target
    }

    /// This reference made from its runs at N and 2N and one more run, at 4N: its N doubled.
    /// `progress` may stop that run partway ([`Stopped`](super::Stopped)).
    pub fn doubled(self, progress: &impl Progress) -> anyhow::Result<Self> {
        let segments = 2 * self.segments;
        let finer = Trajectory::compute_by(
            self.method,
            &self.scene,
            2 * segments,
            self.duration,
            progress,
        )?;
        Ok(Self::of(
            self.method,
            self.scene,
            self.coarse,
            self.fine,
            finer,
            segments,
            self.duration,
        ))
    }

    /// The reference of `method`'s runs from `scene` at N/2, N and 2N (`half`, `coarse`,
    /// `fine`): the order the three show at the frames, and its own error there.
    fn of(
        method: MethodKind,
        scene: Scene,
        half: Trajectory,
        coarse: Trajectory,
        fine: Trajectory,
        segments: usize,
        duration: f64,
    ) -> Self {
        let frames = frame_times(duration, LOG_RATE);
        let (step_coarse, step_fine) = (
            coarse.largest_gap(&half, &frames),
            fine.largest_gap(&coarse, &frames),
        );
        let order = if step_fine > 0.0 {
            (step_coarse / step_fine).log2().clamp(1.0, 2.0)
        } else {
            2.0
        };
        let mut reference = Self {
            scene,
            method,
            half,
            coarse,
            fine,
            segments,
            order,
            duration,
            own_error: 0.0,
        };
        reference.own_error = reference.own_error_over(duration, JUDGE_RATE);
        reference
    }

    /// The reference tip at time `t`.
    pub fn at(&self, t: f64) -> Point {
        self.extrapolated(&self.fine, &self.coarse, t)
    }

    /// The tip at `t` extrapolated from `fine` and the run at half its N, `coarse`.
    fn extrapolated(&self, fine: &Trajectory, coarse: &Trajectory, t: f64) -> Point {
        extrapolate(fine.at(t), coarse.at(t), self.order)
    }
}

impl ConvergedTip for TipReference {
    fn scene(&self) -> Scene {
        self.scene
    }

    fn tip_at(&self, t: f64) -> Point {
        self.at(t)
    }

    /// How far its tip moves when it is made from N and 2N rather than from N/2 and N.
    fn own_error_at(&self, t: f64) -> f64 {
        let coarser = self.extrapolated(&self.coarse, &self.half, t);
        (self.at(t) - coarser).norm()
    }
}

/// The tip extrapolated in N (Richardson) at `order` from a run's tip, `fine`, and the tip of
/// the run at half its N, `coarse`.
pub fn extrapolate(fine: Point, coarse: Point, order: f64) -> Point {
    fine + (fine - coarse) / (2f64.powf(order) - 1.0)
}

/// Instants a time unit at which a reference's own error is also measured between the frames.
pub const REFERENCE_RATE: f64 = 1000.0;

/// Rows a time unit of `references.csv`: every frame ([`LOG_RATE`]) and every
/// 1/[`REFERENCE_RATE`] is a row, so that a reference read back is read at its rows and never
/// between them (near the whip a cubic through every other row misses the row between by up
/// to 1e-3 at 1 000 rows a unit).
pub const REFERENCE_ROWS_RATE: f64 = 3000.0;

/// The first line of `references.csv`, and of any file in its columns.
pub const REFERENCES_HEADER: &str = "scene,t,tip_x,tip_y,own_error";

/// `references.csv`: each reference's tip and its own error ([`ConvergedTip::own_error_at`])
/// every 1/[`REFERENCE_ROWS_RATE`] of a time unit to `duration`, for anyone to hold another
/// solver against, and for `rope study --tolerance-check --references` to read back.
pub fn write_references(
    path: &std::path::Path,
    references: &[impl ConvergedTip],
    duration: f64,
) -> std::io::Result<()> {
    let rows = references.iter().flat_map(|reference| {
        frame_times(duration, REFERENCE_ROWS_RATE)
            .into_iter()
            .map(|t| {
                (
                    reference.scene(),
                    t,
                    reference.tip_at(t),
                    reference.own_error_at(t),
                )
            })
    });
    write_reference_csv(path, rows)
}

/// A CSV of reference tips in the columns of `references.csv`: a row per (scene, t, tip, own
/// error), the tip to 1e-9, for any reference written out (the check's, or one measured
/// beside it by `examples/reference_convergence`).
pub fn write_reference_csv(
    path: &std::path::Path,
    rows: impl IntoIterator<Item = (Scene, f64, Point, f64)>,
) -> std::io::Result<()> {
    use std::io::Write as _;
    let mut out = std::io::BufWriter::new(std::fs::File::create(path)?);
    writeln!(out, "{REFERENCES_HEADER}")?;
    for (scene, t, tip, own) in rows {
        let label = csv_field(&scene.to_string());
        writeln!(out, "{label},{t},{:.9},{:.9},{own:.1e}", tip.x, tip.y)?;
    }
    out.flush()
}

/// `text` as one CSV field: quoted (its quotes doubled) where it holds a comma or a quote, as
/// a shake's label does (`shake (A = 0.1, Ω = 2, from rest)`).
pub fn csv_field(text: &str) -> String {
    match text.contains([',', '"']) {
        true => format!("\"{}\"", text.replace('"', "\"\"")),
        false => text.to_owned(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What the synthetic runs below stand for.
    const METHOD: MethodKind = MethodKind::Chain;
    const SCENE: Scene = Scene::Release { angle_deg: 30.0 };

    /// A path and the runs that err from it by `C(t)/N^1.5`, kept every 1/1000.
    fn runs_around(path: fn(f64) -> Point) -> [Trajectory; 3] {
        let dt = 1e-3;
        [100usize, 200, 400].map(|n| {
            let tips = (0..=3002)
                .map(|i| {
                    let t = i as f64 * dt;
                    let error = Point::new(t * t, t).coords * 0.1 / (n as f64).powf(1.5);
                    path(t) + error
                })
                .collect();
            Trajectory::new(dt, tips)
        })
    }

    #[test]
    fn a_reference_finds_the_order_its_runs_converge_at_and_recovers_their_limit() {
        let path = |t: f64| Point::new(t.sin(), -t.cos());
        let [half, coarse, fine] = runs_around(path);
        let reference = TipReference::of(METHOD, SCENE, half, coarse, fine, 200, 3.0);
        assert!((reference.order - 1.5).abs() < 1e-6, "{}", reference.order);
        for t in [0.0, 0.4321, 1.5, 2.999] {
            assert!((reference.at(t) - path(t)).norm() < 1e-9, "t = {t}");
        }
        // The extrapolations from N, 2N and from N/2, N agree: its own error is round-off.
        assert!(reference.own_error < 1e-9);
        assert!(reference.own_error_over(3.0, REFERENCE_RATE) < 1e-9);
    }

    #[test]
    fn its_own_error_between_the_frames_sees_what_the_frames_miss() {
        // A brief peak between two frames (1/60 apart): a whip the runs resolve differently.
        let peak = |t: f64| (-((t - 1.0 / 120.0) * 2000.0).powi(2)).exp();
        let [mut half, coarse, fine] = runs_around(|t| Point::new(t, 0.0));
        let tips = half
            .tips()
            .iter()
            .enumerate()
            .map(|(i, p)| p + Point::new(0.0, 1e-3 * peak(i as f64 * 1e-3)).coords)
            .collect();
        half = Trajectory::new(1e-3, tips);
        let reference = TipReference::of(METHOD, SCENE, half, coarse, fine, 200, 3.0);
        let at_frames = reference.own_error_over(3.0, LOG_RATE);
        assert!(at_frames < 1e-6, "{at_frames}");
        // The own error it carries is at every instant it judges (JUDGE_RATE): it sees it.
        assert!(reference.own_error > 1e-4, "{}", reference.own_error);
        assert!(reference.own_error_over(3.0, REFERENCE_RATE) > 1e-4);
    }

    #[test]
    fn a_reference_doubled_is_the_one_made_at_its_new_n() {
        // The runs are deterministic: from N = 16 doubled twice, the runs at 32, 64 and 128.
        let scene = Scene::Mode {
            number: 1,
            amplitude: 0.05,
        };
        let refined = TipReference::refined_by(METHOD, &scene, 16, 64, 0.0, 0.5, &|| ()).unwrap();
        let direct = TipReference::compute_by(METHOD, &scene, 64, 0.5).unwrap();
        assert_eq!(refined.segments, 64);
        assert_eq!(refined.order, direct.order);
        assert_eq!(refined.own_error, direct.own_error);
        for t in [0.0, 0.1234, 0.5] {
            assert_eq!(refined.at(t), direct.at(t), "t = {t}");
        }
        // Short of its target, the doubling stops at the largest N allowed.
        let capped = TipReference::refined_by(METHOD, &scene, 16, 63, 0.0, 0.5, &|| ()).unwrap();
        assert_eq!(capped.segments, 16 * 2);
    }

    #[test]
    fn a_doubling_that_cannot_reach_its_target_even_at_second_order_is_not_asked_for() {
        let [half, coarse, fine] = runs_around(|t| Point::new(t.cos(), t.sin()));
        let mut reference = TipReference::of(METHOD, SCENE, half, coarse, fine, 3200, 3.0);
        // A whip's first order, 7.2e-4 at N = 3 200: at second order still 1.8e-4 by 6 400.
        reference.own_error = 7.2e-4;
        reference.order = 1.0;
        assert!(!reference.could_reach(1e-5, 6400));
        // 1.4e-5: at second order 3.5e-6 by 6 400, so the doubling is worth trying.
        reference.own_error = 1.4e-5;
        assert!(reference.could_reach(1e-5, 6400));
        // A third order shown is taken at its word: 7.2e-5 / 8 = 9e-6.
        reference.own_error = 7.2e-5;
        reference.order = 3.0;
        assert!(reference.could_reach(1e-5, 6400));
        reference.order = 2.0;
        assert!(!reference.could_reach(1e-5, 6400));
        // Nothing to double into.
        assert!(!reference.could_reach(1e-5, 3200));
    }

    #[test]
    fn the_references_file_gives_each_tip_and_own_error_at_every_frame_and_thousandth() {
        let [half, coarse, fine] = runs_around(|t| Point::new(t.cos(), t.sin()));
        let reference = TipReference::of(METHOD, SCENE, half, coarse, fine, 200, 3.0);
        let path = std::env::temp_dir().join(format!("rope-refs-{}.csv", std::process::id()));
        write_references(&path, std::slice::from_ref(&reference), 3.0).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        std::fs::remove_file(&path).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], "scene,t,tip_x,tip_y,own_error");
        assert_eq!(lines.len(), 1 + 9001);
        // Every 1/1 000 (t = 1.234) and every frame (t = 1.25 = 75/60) is a row.
        for (row, at) in [(3702, 1.234), (3750, 1.25)] {
            let fields: Vec<&str> = lines[1 + row].split(',').collect();
            assert_eq!(fields[0], SCENE.to_string());
            let t: f64 = fields[1].parse().unwrap();
            assert!((t - at).abs() < 1e-12, "{t}");
            let x: f64 = fields[2].parse().unwrap();
            assert!((x - t.cos()).abs() < 1e-8, "{x}");
        }
    }
}
