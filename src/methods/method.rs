//! What a numerical method is: the [`Method`] trait the driver steps, the [`Observation`] it
//! fills for output, and the [`Descriptor`] in which each method says everything else about
//! itself once. Also the checks and messages every method shares.

use super::accurate_step::{AccurateStep, TOLERANCE_STEP_GRID, whole_division};
use crate::error::{ConfigError, Diverged};
use crate::model::{Energy, Scene, SupportNow};
use nalgebra::Vector2;

/// The tension the stability limits are written for, in m g: about that of a swing from
/// rest in its first time units (the report saw the support tension below 5/4 in its short
/// runs; a long swing's whips reach 3, where the rods take substeps).
pub const TENSION_MAX: f64 = 1.5;

/// How far past the tolerance step a rotation bound may loosen
/// ([`Descriptor::rotation_scale`]): tenfold, to half a radian a step for the midpoint rule
/// (from the horizontal at N = 8 and k = 0.1, 3.6 solves a step and no Newton failing) and a
/// fifth of one for an RK4 substep of the chain (a turn's local error θ⁵/120, 3e-6 rad).
/// `rattle` keeps its bound: loosened, its runs at k = 0.1 grew dearer, not cheaper.
pub const LOOSEST_ROTATION: f64 = 10.0;

/// The state of the string at one instant, for output: everything per segment.
#[derive(Clone, Debug, Default)]
pub struct Observation {
    /// Segment angles φ_i below the horizontal.
    pub angle: Vec<f64>,
    /// Their unit tangents (cos φ_i, sin φ_i) as the method carries them beside its angles
    /// (equal to the angles' sines and cosines to round-off), where it does; empty where it
    /// does not, and the frame works them out from the angles.
    pub tangent: Vec<Vector2<f64>>,
    /// φ̇_i.
    pub angular_velocity: Vec<f64>,
    /// φ̈_i.
    pub angular_acceleration: Vec<f64>,
    /// Tension F_i on each segment (F ≥ 0 for a string; 0 at the free end).
    pub tension: Vec<f64>,
}

/// How an adaptive method's own steps went, inside the driver's steps: for the summary.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct StepStatistics {
    /// Steps taken (each a length of its own, the driver's steps split where the state asks).
    pub steps: u64,
    /// The shortest step taken.
    pub smallest_step: f64,
    /// The largest |θ̇| at the start of a step: what made the steps shrink.
    pub fastest_rotation: f64,
    /// Steps whose Newton failed and that were retaken at half the length.
    pub newton_failures: u64,
    /// Linear solves of Newton, in all.
    pub solves: u64,
    /// Kinetic energy the velocity projections removed and the rescale put back, summed.
    pub restored_energy: f64,
    /// The scheme's own energy error from round-off between projections, which the rescale
    /// took back too, summed in absolute value.
    pub roundoff_energy: f64,
    /// Energy left unrestored where the string was too nearly at rest to rescale its
    /// velocities, summed in absolute value.
    pub unrestored_energy: f64,
}

/// A numerical method advancing the string in time. Pure: state in, state out, no I/O.
pub trait Method: Send {
    /// What the method says of itself.
    fn descriptor(&self) -> &'static Descriptor;
    /// Number of segments N.
    fn segments(&self) -> usize;
    /// Time step k of the driver (for a method that splits it, its largest step).
    fn dt(&self) -> f64;
    /// Simulated time reached: steps × k (every step has the same length).
    fn time(&self) -> f64 {
        self.steps() as f64 * self.dt()
    }
    /// Steps taken.
    fn steps(&self) -> u64;
    /// Advances one time step, or says why the new state cannot be trusted.
    fn step(&mut self) -> Result<(), Diverged>;
    /// Total energy now (eqs. 13–16), second-order accurate in the time step, in the room
    /// (under a shaken support, the kinetic energy of the support's motion included).
    fn energy(&self) -> Energy;
    /// A moving support now: where it is in the room, how it moves, and the work W it has
    /// done on the string since the start. `None` for a support fixed at the origin (for a
    /// method that carries no other, always).
    fn support(&self) -> Option<SupportNow> {
        None
    }
    /// E − W: what the string's energy would be had the support done no work, which the ideal
    /// string keeps (E itself under a fixed support). Its change is the balance E − E₀ − W.
    fn energy_less_work(&self) -> f64 {
        self.energy().total() - self.support().map_or(0.0, |s| s.work)
    }
    /// The tension at the support, s = 0, from the latest solve: the force the support
    /// bears along the string (a string hanging at rest: m g = 1, whatever N). Not the first
    /// of `Observation::tension`, which sits [`Descriptor::tension_first_at`] segments below.
    fn support_tension(&self) -> f64;
    /// The segment angles φ_i now, support … tip: the shape, without solving for anything.
    fn angles(&self) -> &[f64];
    /// The rods' lengths, support … tip, where they are not all 1/N (graded rods, summing to
    /// 1); `None` for N equal segments.
    fn lengths(&self) -> Option<&[f64]> {
        None
    }
    /// The free end in the support's frame, Σ l_i (cos φ_i, sin φ_i) (eqs. 14–15 at the last
    /// node), what the live estimate compares at every step it shares with its shadow: by
    /// default from the angles, a sine and cosine a rod; a method that holds its rods'
    /// tangents at these very angles sums those instead.
    fn tip(&self) -> crate::model::geometry::Point {
        crate::model::geometry::tip_of(self.angles(), self.lengths())
    }
    /// The largest joint gap |g_j| after the latest step, for a method whose rods are held
    /// together by constraints it solves for (it must stay at round-off); `None` for a
    /// method whose string cannot come apart by construction.
    fn constraint_residual(&self) -> Option<f64> {
        None
    }
    /// |G v|, the largest relative velocity of a joint's two sides, for a method whose
    /// velocities can leave the constraints between projections (before its latest
    /// projection); `None` where they cannot.
    fn velocity_residual(&self) -> Option<f64> {
        None
    }
    /// How the method's own steps went, for a method that chooses them; `None` for a method
    /// of fixed steps (or integer substeps).
    fn step_statistics(&self) -> Option<StepStatistics> {
        None
    }
    /// Fills `out` with the state now (tension freshly solved for the current time).
    fn observe(&mut self, out: &mut Observation);
    /// A copy of the method in its current state.
    fn box_clone(&self) -> Box<dyn Method>;
}

/// The largest of 1, 2 or 5 × 10^k not above `x`: default steps are round numbers, so that
/// whole durations are whole numbers of steps.
pub fn round_down_nicely(x: f64) -> f64 {
    let decade = 10f64.powf(x.log10().floor());
    let mantissa = x / decade;
    let nice = if mantissa >= 5.0 {
        5.0
    } else if mantissa >= 2.0 {
        2.0
    } else {
        1.0
    };
    nice * decade
}

/// The tension at the support of a string at rest, from its first rod's tension `first`
/// (at the rod's middle, h/2 below) and that rod's angle: at rest the tension's slope along
/// the string is gravity's alone, F_s = −sin φ, so F(0) = F_first + (h/2) sin φ_0. What the
/// rods report before their first step, whose solves then give the support's force itself.
pub fn support_tension_at_rest(first: f64, angle: f64, segments: usize) -> f64 {
    first + 0.5 / segments.max(1) as f64 * angle.sin()
}

/// Checks what every method needs of a time step.
pub(crate) fn validate_dt(dt: f64) -> Result<(), ConfigError> {
    if dt.is_finite() && dt > 0.0 {
        Ok(())
    } else {
        Err(ConfigError::TimeStep(dt))
    }
}

/// Checks what every method needs of a segment count.
pub(crate) fn validate_segments(method: &Descriptor, segments: usize) -> Result<(), ConfigError> {
    if segments < method.min_segments {
        return Err(ConfigError::TooFewSegments {
            method: method.name,
            segments,
            min: method.min_segments,
        });
    }
    Ok(())
}

/// Where the time step stands against the method's estimated stability limit, for the
/// reason of a divergence: "k = … exceeds the estimated limit …" or "… is within …".
pub fn stability_hint(method: &Descriptor, segments: usize, dt: f64) -> String {
    let limit = method.stability_limit(segments);
    if dt > limit {
        format!("k = {dt:.3e} exceeds the estimated limit {limit:.3e}")
    } else {
        format!("k = {dt:.3e} is within the estimated limit {limit:.3e}")
    }
}

/// The divergence of step `steps + 1` of a method whose `what` became non-finite.
pub(crate) fn non_finite(
    method: &Descriptor,
    segments: usize,
    dt: f64,
    steps: u64,
    what: &str,
) -> Diverged {
    Diverged {
        step: steps + 1,
        time: (steps + 1) as f64 * dt,
        reason: format!(
            "{what} became non-finite ({})",
            stability_hint(method, segments, dt)
        ),
    }
}

/// Checks the state a chain of `segments` rods reached after step `steps + 1`: its angles and
/// rates (`values`) and support tension must be finite, or the step diverged.
pub(crate) fn check_finite<'a>(
    method: &Descriptor,
    segments: usize,
    dt: f64,
    steps: u64,
    mut values: impl Iterator<Item = &'a f64>,
    support_tension: f64,
) -> Result<(), Diverged> {
    if values.all(|v| v.is_finite()) && support_tension.is_finite() {
        Ok(())
    } else {
        Err(non_finite(
            method,
            segments,
            dt,
            steps,
            "the angle or the rate",
        ))
    }
}

/// Builds a method at rest in a scene, with N segments and time step k, validating what it
/// needs.
pub type Builder = fn(&Scene, usize, f64) -> Result<Box<dyn Method>, ConfigError>;

/// Everything the crate needs to know of a method, in one place. Each method's file defines
/// its own as `DESCRIPTOR`.
#[derive(Clone, Copy, Debug)]
pub struct Descriptor {
    /// Name on the command line, in summaries and on charts.
    pub name: &'static str,
    /// Fewest segments the method can run with.
    pub min_segments: usize,
    /// C of the estimated stability limit k < C h / sqrt([`TENSION_MAX`]).
    pub courant: f64,
    /// What the stability limit means for this method, as the stability map labels it.
    pub limit_meaning: &'static str,
    /// What a time step past the stability limit does to this method, as a sentence for the
    /// user who asks for one (or who reads the limit printed beside the default step).
    pub past_limit: &'static str,
    /// Whether the method keeps the energy exactly (to round-off), whatever the step: the
    /// one to suggest when another strays.
    pub keeps_energy: bool,
    /// Whether the method suits a run left going for long at a steady cost per time unit:
    /// the one to suggest for a long run (with no blow-up of its own, [`Descriptor::blow_up`]).
    pub steady_cost: bool,
    /// For a method that blows up in a long run at any step: when it did, from the release
    /// at 30°, in every run of `rope study --blow-up 200` (`assets/blow-up/`), by N. Empty
    /// for a method that stays stable for ever.
    pub blow_up: &'static [BlowUp],
    /// The default time step, as a fraction of the stability limit (then rounded down to
    /// 1, 2 or 5 × 10^k).
    pub default_step_fraction: f64,
    /// For a method stable at any step, the step its tip's accuracy needs, which the default
    /// step is never below: the limit shrinks as h, where what the tip needs shrinks slower.
    /// `None`: the default is the fraction of the limit alone.
    pub accurate_step: Option<AccurateStep>,
    /// Whether a time step past the limit is refused (unless `--allow-unstable`): true for a
    /// method that blows up there, false for one that stays stable and only costs more.
    pub refuses_unstable_step: bool,
    /// The step `--tolerance` runs at, as a fraction of the stability limit, where it is not
    /// the default step: one at which the method's worst tip error to t = 3 is still that of
    /// its default step (its spatial error), within 2.5 % in every scene and N probed
    /// (`scripts/tolerance-step.sh`). `None`: the default step. The default is chosen for the
    /// energy over long runs; a tip tolerance over a finite run need not pay for it.
    pub tolerance_step_fraction: Option<f64>,
    /// CPU cost of one step per segment, in ns (`cargo bench --bench step`, N = 1000).
    pub ns_per_segment_step: f64,
    /// Where the first of the method's tensions (`Observation::tension`) sits along the
    /// string, in segments from the support; the others follow a segment apart. The rods'
    /// tension acts along each rod: 0.5, its middle. The seed's F_i sit at s = (i + 1) h
    /// (F_{N−1} = 0 is the free end): 1.
    pub tension_first_at: f64,
    /// What the method discretizes the string into. Methods of one discretization share its
    /// spatial error: at their tolerance steps their worst tip errors agree to within the
    /// probe's scatter (`scripts/tolerance-step.sh`), so `--tolerance`'s pilots fly only the
    /// cheapest of them.
    pub discretization: &'static str,
    /// Memory of the method's state per segment, in bytes (what its vectors hold).
    pub bytes_per_segment: usize,
    /// The order of accuracy in h the method is built to have (1 for a first-order scheme):
    /// what Richardson's extrapolation and the live error estimate divide by 2^p − 1 with.
    pub order_in_h: u32,
    /// Chart colours: its coarsest and its finest runs, shades between.
    pub colours: ([u8; 3], [u8; 3]),
    /// Builds the method at rest in a scene, validating what it needs.
    pub build: Builder,
    /// What the method refuses of a valid scene whatever N and k: a scene or angle it cannot
    /// start from (`seed` from the horizontal, the graded rods but from a release). Its
    /// builder refuses the same; a run is checked by it before anything is built
    /// ([`MethodKind::starts_from`](super::MethodKind::starts_from)).
    pub starts_from: fn(&Scene) -> Result<(), ConfigError>,
    /// Whether `--tolerance` may choose the method for a scene it can start from, for a run
    /// to the given duration: where its cost is what [`Descriptor::ns_per_segment_step`]
    /// predicts (every scene but for the graded rods, whose end rods spin on near the
    /// horizontal, and, past t = 3, below 40°).
    pub plannable: fn(&Scene, f64) -> bool,
}

/// When a method blew up at one N, over the steps of the blow-up map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BlowUp {
    pub segments: usize,
    /// The earliest and the latest time of divergence over the map's steps.
    pub earliest: f64,
    pub latest: f64,
}

impl Descriptor {
    /// When the method is known to blow up at `segments` segments: the map's row at that N,
    /// or between two rows the earlier of the two (beyond the rows, the nearest).
    pub fn blow_up_at(&self, segments: usize) -> Option<BlowUp> {
        let below = self.blow_up.iter().rev().find(|b| b.segments <= segments);
        let above = self.blow_up.iter().find(|b| b.segments >= segments);
        match (below, above) {
            (Some(a), Some(b)) if a.earliest <= b.earliest => Some(*a),
            (_, Some(b)) => Some(*b),
            (Some(a), None) => Some(*a),
            (None, None) => None,
        }
    }

    /// Estimated largest stable time step at `segments` segments: k < C h / sqrt(F_max).
    pub fn stability_limit(&self, segments: usize) -> f64 {
        self.courant / (segments as f64 * TENSION_MAX.sqrt())
    }

    /// The default time step at `segments` segments for the horizontal release, whose free
    /// end whips hardest, or any scene not known to be milder: what studies, plans and
    /// `--tolerance`'s steps start from.
    pub fn default_dt(&self, segments: usize) -> f64 {
        self.default_with(segments, self.accurate_step.map(|a| a.at(segments)))
    }

    /// The default time step at `segments` segments in `scene`: [`Descriptor::default_dt`],
    /// or where the method's accurate step eases for the scene ([`AccurateStep::ease`]), the
    /// eased step. What a run takes when `--dt` is not given.
    pub fn default_step(&self, scene: &Scene, segments: usize) -> f64 {
        self.default_with(
            segments,
            self.accurate_step.map(|a| a.in_scene(scene, segments)),
        )
    }

    fn default_with(&self, segments: usize, accurate: Option<f64>) -> f64 {
        let limited =
            round_down_nicely(self.default_step_fraction * self.stability_limit(segments));
        accurate.map_or(limited, |a| limited.max(a))
    }

    /// The step `--tolerance` runs at `segments` segments:
    /// [`Descriptor::tolerance_step_fraction`] of the limit, brought down to 1/(120 m) for a
    /// whole m (frames at 60, 30, 20, … per time unit then fall on even steps, which the live
    /// estimate's shadow shares, and a duration of whole frames is whole steps), and never
    /// below the default step; the default step where the method has no fraction of its own.
    pub fn tolerance_dt(&self, segments: usize) -> f64 {
        let default = self.default_dt(segments);
        let Some(fraction) = self.tolerance_step_fraction else {
            return default;
        };
        let wanted = fraction * self.stability_limit(segments);
        whole_division(TOLERANCE_STEP_GRID, wanted).max(default)
    }

    /// min(1, k / k_default): what a method's substep bounds are multiplied by, so that below
    /// the default step a finer step refines every substep (the whip's too) in proportion,
    /// and at the default step and above the bounds are as tuned.
    pub fn refinement(&self, segments: usize, dt: f64) -> f64 {
        (dt / self.default_dt(segments)).min(1.0)
    }

    /// What a method's bound on a rod's rotation per (sub)step is multiplied by in `scene`:
    /// the [`refinement`](Self::refinement) up to [`coarse_above`](Self::coarse_above), and
    /// past it k over that, at most [`LOOSEST_ROTATION`]. A step asked for that coarse is
    /// then taken as asked where the rods turn slowly (from 30° at N = 12 and k = 0.1, a pair
    /// of 0.05 for each step, where the fixed bound split each into four or six), and still
    /// split where the free end whips. What keeps an explicit method stable, its Courant
    /// bound, stays as tuned. Below that nothing changes, so no run that `--tolerance` plans
    /// or pilots, nor any default run, nor the live estimate's shadow of one (N/2 rods at 2k,
    /// and neither k_tolerance nor the default step grows with N), is touched.
    pub fn rotation_scale(&self, scene: &Scene, segments: usize, dt: f64) -> f64 {
        let loosening = dt / self.coarse_above(scene, segments);
        self.refinement(segments, dt) * loosening.clamp(1.0, LOOSEST_ROTATION)
    }

    /// Whether a step `dt` at `segments` in `scene` is coarse: past
    /// [`coarse_above`](Self::coarse_above), where [`rotation_scale`](Self::rotation_scale)
    /// loosens a method's bounds. No run that `--tolerance` plans or pilots, no default run
    /// and no live estimate's shadow of one has a coarse step.
    pub fn is_coarse(&self, scene: &Scene, segments: usize, dt: f64) -> bool {
        dt > self.coarse_above(scene, segments)
    }

    /// Twice the larger of the step `--tolerance` runs at and the scene's default step
    /// ([`default_step`](Self::default_step), above the tolerance step only where a calm
    /// release eases it): the step past which a step is coarse.
    pub fn coarse_above(&self, scene: &Scene, segments: usize) -> f64 {
        2.0 * self
            .tolerance_dt(segments)
            .max(self.default_step(scene, segments))
    }

    /// The Courant number C = k N sqrt(F_max) that a step `dt` at `segments` amounts to.
    pub fn courant_of(segments: f64, dt: f64) -> f64 {
        dt * segments * TENSION_MAX.sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::methods::MethodKind;

    #[test]
    fn a_tolerance_step_is_a_whole_fraction_of_the_frame_grid_within_its_fraction_of_the_limit() {
        for method in MethodKind::ALL {
            let d = method.descriptor();
            for n in [2, 4, 16, 50, 100, 283, 491, 1000, 10_000] {
                if n < d.min_segments {
                    continue;
                }
                let (k, default) = (d.tolerance_dt(n), d.default_dt(n));
                assert!(
                    k >= default,
                    "{method} N = {n}: {k} below the default {default}"
                );
                let Some(fraction) = d.tolerance_step_fraction else {
                    assert_eq!(k, default, "{method} N = {n}");
                    continue;
                };
                if k > default {
                    assert!(
                        k <= fraction * d.stability_limit(n) * (1.0 + 1e-12),
                        "{method} N = {n}"
                    );
                    let m = TOLERANCE_STEP_GRID / k;
                    assert!((m - m.round()).abs() < 1e-9, "{method} N = {n}: k = {k}");
                    // The largest such step: one whole part fewer would pass the fraction.
                    let larger = TOLERANCE_STEP_GRID / (m.round() - 1.0);
                    assert!(m.round() == 1.0 || larger > fraction * d.stability_limit(n));
                }
            }
        }
        // The chain at N = 491: the limit 6.65e-4, the step 1/1560.
        let chain = MethodKind::Chain.descriptor();
        assert!((chain.tolerance_dt(491) - 1.0 / 1560.0).abs() < 1e-15);
    }

    #[test]
    fn a_rotation_bound_loosens_only_past_twice_the_tolerance_step_so_no_planned_run_or_shadow_moves()
     {
        let scenes = [
            Scene::Release { angle_deg: 0.0 },
            Scene::Release { angle_deg: 4.0 },
            Scene::Release { angle_deg: 30.0 },
            Scene::Fold { gap: 0.1 },
        ];
        for method in MethodKind::ALL {
            let d = method.descriptor();
            for scene in &scenes {
                let (mut before, mut default_before) = (f64::INFINITY, f64::INFINITY);
                for n in d.min_segments.max(4)..=2_000 {
                    let (k, default) = (d.tolerance_dt(n), d.default_step(scene, n));
                    // Neither k_tolerance nor the default step grows with N, so a shadow
                    // (N/2 rods, 2k) stays below its own coarse step whenever its run does.
                    assert!(k <= before, "{method} N = {n}: {k} above {before}");
                    assert!(default <= default_before, "{method} {scene:?} N = {n}");
                    (before, default_before) = (k, default);
                    let top = k.max(default);
                    for dt in [default, k, 2.0 * top] {
                        let scale = d.rotation_scale(scene, n, dt);
                        assert_eq!(scale, d.refinement(n, dt), "{method} {n}");
                        assert!(!d.is_coarse(scene, n, dt), "{method} N = {n} at k = {dt}");
                        let half = n / 2;
                        if half >= d.min_segments && dt <= top {
                            let shadow = 2.0 * dt;
                            assert_eq!(
                                d.rotation_scale(scene, half, shadow),
                                d.refinement(half, shadow),
                                "{method} N = {n}'s shadow at k = {dt}"
                            );
                            assert!(!d.is_coarse(scene, half, shadow), "{method} {n}'s shadow");
                        }
                    }
                    // Past it, in proportion to the step, and at most tenfold; such a step is
                    // coarse (the midpoint rule then takes it whole where the rods allow).
                    let coarse = 2.0 * top * (1.0 + 1e-12);
                    assert!(d.is_coarse(scene, n, coarse), "{method} N = {n}");
                    let thrice = d.rotation_scale(scene, n, 6.0 * top) / d.refinement(n, 6.0 * top);
                    assert!((thrice - 3.0).abs() < 1e-12, "{method} N = {n}: {thrice}");
                    assert_eq!(d.rotation_scale(scene, n, 1e3 * top), LOOSEST_ROTATION);
                }
            }
        }
    }

    #[test]
    fn a_calm_release_takes_a_longer_default_step_than_the_horizontal_and_other_scenes_do_not() {
        let midpoint = MethodKind::Midpoint.descriptor();
        let release = |angle_deg| Scene::Release { angle_deg };
        // The horizontal release keeps the rule: 1/1080 at N = 1 000.
        let horizontal = midpoint.default_step(&release(0.0), 1_000);
        assert_eq!(horizontal, midpoint.default_dt(1_000));
        assert!((horizontal - 1.0 / 1_080.0).abs() < 1e-15);
        // From 10° on, twice the rule's step brought onto the grid: 1/600 at N = 1 000, and
        // twice the largest, 2e-3, at N = 400.
        for angle in [10.0, 30.0, 90.0] {
            let k = midpoint.default_step(&release(angle), 1_000);
            assert!((k - 1.0 / 600.0).abs() < 1e-15, "{angle}°: {k}");
            assert_eq!(midpoint.default_step(&release(angle), 400), 2e-3);
        }
        // Between, linear in the angle: 5° is 1.5 times the rule before the grid.
        let half = midpoint.default_step(&release(5.0), 1_000);
        assert!((half - 1.0 / 720.0).abs() < 1e-15, "{half}");
        // Other scenes and methods with no accurate step keep the default.
        for scene in [
            Scene::Fold { gap: 0.1 },
            Scene::Mode {
                number: 1,
                amplitude: 0.05,
            },
        ] {
            assert_eq!(midpoint.default_step(&scene, 1_000), horizontal);
        }
        let rattle = MethodKind::Rattle.descriptor();
        assert_eq!(
            rattle.default_step(&release(30.0), 1_000),
            rattle.default_dt(1_000)
        );
    }

    #[test]
    fn a_study_compares_every_method_of_a_steady_cost_unless_told() {
        let steady: Vec<MethodKind> = MethodKind::ALL
            .into_iter()
            .filter(|m| m.descriptor().steady_cost)
            .collect();
        assert_eq!(steady, MethodKind::STUDIED);
        assert!(!MethodKind::STUDIED.contains(&MethodKind::Graded));
    }
}
