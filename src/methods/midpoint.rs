//! The energy–momentum midpoint rule on the chain of N uniform rigid rods: the same model and
//! coordinates as `rattle` (so second order in h), stepped by a discrete-gradient scheme whose
//! energy is kept exactly, whatever the sequence of step lengths. Its steps can then shrink at
//! a snap of the free end and grow again, at no price in energy.
//!
//! **Coordinates.** Rod centres c_i and angles θ_i, velocities v_i and rates ω_i; M =
//! diag(h, h, h³/12) per rod, gravity f = (0, h) per rod (y down), the joint gaps g_j of
//! `rattle` (`constraint_matrix.rs`). Under a shaken support the rods live in its frame,
//! where gravity is h (−ẍ_s, 1), taken at each step's middle: its potential is linear in
//! the positions, so the step below keeps E′ + Σ ẍ_s(t_mid) ΔX exactly, and with it the
//! balance E − E₀ − W of the room's energy and the support's work (docs/physics.md).
//!
//! **A step of length k** (Gonzalez 1999; Betsch 2005):
//! * (q₁ − q₀)/k = (v₀ + v₁)/2,
//! * M (v₁ − v₀)/k = f − Ḡᵀ λ,
//! * g(q₁) = 0,
//!
//! with Ḡ the discrete gradient of g: Ḡ (q₁ − q₀) = g(q₁) − g(q₀) exactly. Its centre columns
//! are the constant ±I; rod i's angular column is (h/2) b_i with b_i = sinc(Δθ_i/2) n(θ_i +
//! Δθ_i/2), because e(θ₁) − e(θ₀) = 2 sin(Δθ/2) n(θ_mid). Then ΔT = v̄ᵀ M Δv = Δqᵀ(f − Ḡᵀλ) =
//! −ΔV − λᵀ(g(q₁) − g(q₀)) = −ΔV: the energy is kept to the Newton tolerance and round-off.
//!
//! **Solving it.** With μ = k²λ/2 the centres follow from μ linearly,
//! Δc_i = k v_i + (k²/2) ĝ + (μ_i − μ_{i+1})/h, and Newton runs on (Δθ, μ) together: the
//! Δθ-block of its Jacobian is
//! diagonal, and the Schur complement in μ is block-tridiagonal with 2×2 blocks, `rattle`'s
//! pattern but not symmetric (W_i = 3 a_i b_iᵀ / d_i in place of 3 n_i n_iᵀ, a_i = n(θ_i¹)).
//! One forward pass evaluates the residuals and eliminates; one backward pass solves and
//! updates. Its guess carries μ/k² and each rod's torque over from the last two steps,
//! extrapolated to the step's middle: the torque, a small difference of the large forces at
//! a rod's two ends, is guessed far better so than from the μ guessed (from 30° to t = 3 at
//! N = 1 000, 2.19 solves a step where the turns from the μ guessed took 2.43, both with the
//! Jacobian refreshed down to a correction of 1e-6). The state
//! carries increments: v₁ = 2Δq/k − v₀ from the solved Δq, never from differences of
//! absolute positions (whose round-off would become 1e-16/k velocity noise).
//!
//! **The velocity constraint.** The scheme holds G v = 0 only on average, Ḡ (v₀ + v₁) = 0; at
//! the nodes G(q)v is an undamped (−1)ⁿ mode, and the energy of the motion the joints allow
//! would drift from the kept energy. So the steps go in pairs, and after each pair the
//! velocities are projected M-orthogonally onto G(q)v = 0 (over a pair the mode nearly
//! cancels, so the projection removes little), then scaled so that the energy is the starting
//! energy again: what the projection removed and the round-off since the last projection go
//! back, and are counted ([`StepStatistics`]). docs/physics.md says what this does. (A
//! coarse step taken whole, below, is projected alone.)
//!
//! **Steps that follow the motion.** A step of the driver (k_max, `--dt`) is split into an
//! even number of equal steps no longer than [`ROTATION`] · s / max|θ̇|, a smooth function
//! of the state (s = min(1, k_max/k_default), and past twice the tolerance step
//! k_max/(2 k_tolerance), at most tenfold: [`Descriptor::rotation_scale`]), the rest of the
//! driver's step shared equally among the steps it still needs, so that the last lands
//! exactly on the driver's time; in the calm a driver step is one pair. A coarse driver step
//! ([`Descriptor::is_coarse`]: past twice the tolerance step, which no default, planned or
//! shadow run has) is taken whole where the rods allow a step that long, and projected after
//! it: from 30° at N = 8 and k = 0.1 to t = 1, 10 steps and 41 solves where pairs took 20 and
//! 63, the tip within 5.3e-4 of the converged string at t = 0.1, …, 1 where pairs kept it
//! within 8.2e-4 (both below the 1.3e-3 of eight rods at fine steps: the time error partly
//! cancels the rods' own), and 3.9e-5 of kinetic energy restored after the projections where
//! pairs restored 7.8e-7. A Newton
//! that fails retakes its step at half the length (counted); past [`MIN_STEP_FRACTION`] of
//! k_max the run has diverged.

use super::constraint_matrix::{ConstraintMatrix, Passed, eliminate};
use super::joint_forces::ForceSolver;
use super::method::{self, Descriptor, Method, Observation, StepStatistics};
use crate::error::{ConfigError, Diverged};
use crate::model::Energy;
use crate::model::geometry;
use crate::model::{Scene, SupportLedger, SupportNow};
use nalgebra::{Matrix2, Vector2};

/// C of the estimate k = C h / sqrt(F_max) past which steps are split to follow the state;
/// the method never blows up past it, it pays for the extra steps.
const COURANT: f64 = 0.4;
/// Largest rotation of a rod per step, k · max|θ̇|, from the default step to twice the
/// tolerance step; a finer `--dt` tightens it in proportion, so that a finer step refines the
/// whip too, and a coarser one loosens it ([`Descriptor::rotation_scale`]).
pub const ROTATION: f64 = 0.05;

/// Newton stops when what its last correction leaves moves no angle by more than this
/// (radians) and no joint by more than this (string lengths): about the correction times its
/// contraction from the one before (the simplified Newton converges at least linearly), or,
/// at the first iteration, the correction itself. Before, it stopped at a correction of 1e-10
/// itself, one iteration later: from 30° at N = 1 000 to t = 3 the tip moved by at most
/// 4.4e-14 at 1 000 frames a unit, with 2.4 solves a step where there had been 3.0; the bare
/// scheme's energy from the horizontal, over 28 000 random steps, strayed by 6.6e-14 where it
/// had strayed by 2.0e-14 (`tests/midpoint_physics.rs`; since [`REFRESH`], 5.9e-12).
///
/// The contraction read at the second solve is the first solve's, a Newton step on a fresh
/// Jacobian; the kept Jacobian contracts less where one rod's turn was guessed badly (by
/// factors of 0.03 to 0.05 from 30° at N = 1 000, where a bend passes), so a step stopped at
/// its second solve may leave 0.03 to 0.05 of that solve's correction, a few 1e-10 at most,
/// not 1e-11. Stopping at 3e-11 or 1e-10 would save 6 or 10 % of the solves but move the
/// horizontal release's free fall from t²/2 by 7.3e-12 or 1.2e-11 where it is 5.7e-12
/// (docs/measurements.md, "The fine rope: Newton's loops by kind, the shadow's states in
/// batches").
const CORRECTION: f64 = 1e-11;
/// Newton refreshes its Jacobian until its correction falls below this; after, it keeps it
/// (simplified Newton). A step's first correction is mostly 1e-5 to 1e-4 (from 30° at
/// N = 1 000), so its second solve keeps the first's Jacobian: 16 % fewer instructions a step
/// there than at 1e-6, where it refreshed. The tip moves by at most 1.8e-11; the last solve
/// converges linearly rather than quadratically, so the bare scheme's energy over 28 000
/// random steps strays by 5.9e-12 (at 1e-6, 5.0e-14): it is kept to the Newton tolerance
/// rather than below it, and a run's energy is put back after every pair as before
/// (docs/measurements.md).
const REFRESH: f64 = 1e-4;
/// Newton iterations before a step counts as failed.
const MAX_ITERATIONS: usize = 12;
/// The shortest step, as a fraction of the driver's, before a failing Newton is a divergence.
pub const MIN_STEP_FRACTION: f64 = 1.0 / 1_048_576.0; // 2^-20
/// The largest relative change of the kinetic energy the rescale may make; beyond it (a
/// string all but at rest) the energy is left as the projection made it, and the difference
/// counted as not restored.
const RESCALE_LIMIT: f64 = 1e-2;

/// What the midpoint rule says of itself (see [`Descriptor`]).
pub const DESCRIPTOR: Descriptor = Descriptor {
    name: "midpoint",
    // One rod is a rigid pendulum, two already bend.
    min_segments: 2,
    courant: COURANT,
    limit_meaning: "steps shrink past about k = C h / sqrt(F_max)",
    past_limit: "its own steps shrink until the fastest rod turns at most 0.05 rad in one (up to 0.5 rad for a --dt over twice the step --tolerance takes), so it stays stable at any --dt: the limit only sets the default step at small N (up to N = 100 from the horizontal)",
    keeps_energy: true,
    steady_cost: true,
    blow_up: &[],
    // Two fifths of the limit (1e-3 at N = 100): a pair of steps of 5e-4, `rattle`'s step.
    default_step_fraction: 0.4,
    // Past N = 100, what its tip needs instead: k = 0.8 h (1600 / N)^0.4, at most 1e-3, on
    // the 1/(120 m) grid below it (1/1080 at N = 1 000, 1/2040 at 1 600, 1/5280 at 3 200).
    // Its time error goes as k² N^2.8 from 0° (a finer rope resolves a faster whip), so the
    // step holds that error near a fixed share of the spatial error (the distance to 2N)
    // from N = 800 up, and the 1e-3 cap below. From 0°, 30° and 80° to t = 3, at every step:
    // `cargo run --release --example midpoint_step`, docs/measurements.md. Its own steps still
    // shrink where a rod turns fast. That is the horizontal release's step, whose free end
    // whips hardest; from 10° below the horizontal on, twice it (1/600 at N = 1 000, 2e-3 up
    // to N = 800), and 1 to 2 times between: the time error there stays at most 0.40 of the
    // spatial error (1° at N = 1 000 and 1 600), where the rule's holds 0.62 from 0°, in
    // up to half the steps. From 0° to 80° at N = 100 to 3 200:
    // `cargo run --release --example release_step`, docs/measurements.md.
    accurate_step: Some(crate::methods::accurate_step::AccurateStep {
        times_h: 0.8,
        from: 1600,
        shrink: 0.4,
        largest: 1e-3,
        whip_to_deg: 0.0,
        calm_from_deg: 10.0,
        calm_times: 2.0,
    }),
    refuses_unstable_step: false,
    // The limit: the worst tip error to t = 3 within 1.5 % of the default step's in every
    // scene and N probed, with 2.5 times fewer steps (`scripts/tolerance-step.sh`).
    tolerance_step_fraction: Some(1.0),
    // A pair of steps and its projection (`cargo bench --bench step`, N = 1000), before its
    // loops lost their divisions (3 to 12 % less since: docs/measurements.md); left so that
    // `--tolerance` chooses as the committed check measured.
    ns_per_segment_step: 348.0,
    tension_first_at: 0.5,
    discretization: "rods",
    // The state (centre, angle, tangent, velocity, rate: 64), Newton's unknowns and guesses (Δθ, μ,
    // two past μ/k², two past torques: 72), its per-rod and per-joint blocks (slope, end normal,
    // chord, F, U, gap, y, pivot, gain: 208), A's factorisation for the projection (112; it
    // projects the velocities in place), the observer's joint-force solve (96).
    bytes_per_segment: 64 + 72 + 208 + 112 + 96,
    order_in_h: 2,
    colours: ([200, 170, 240], [90, 40, 160]),
    build: |scene, segments, dt| Ok(Box::new(Midpoint::new(scene, segments, dt)?)),
    // It starts from any valid scene.
    starts_from: |_| Ok(()),
    plannable: |_, _| true,
};

/// sin x, cos x, sinc x = sin x / x and its derivative, by series where |x| is small (their
/// truncation is below round-off there) and by the library elsewhere.
#[inline(always)]
fn half_angle(x: f64) -> (f64, f64, f64, f64) {
    if x.abs() < 0.1 {
        // Multiplied by reciprocals, as `geometry::turned` is: divided by, these constants
        // were a step's longest stalls (docs/measurements.md).
        let x2 = x * x;
        let sinc = 1.0
            - x2 * (1.0 / 6.0)
                * (1.0 - x2 * (1.0 / 20.0) * (1.0 - x2 * (1.0 / 42.0) * (1.0 - x2 * (1.0 / 72.0))));
        let cos = 1.0
            - x2 * 0.5
                * (1.0
                    - x2 * (1.0 / 12.0)
                        * (1.0
                            - x2 * (1.0 / 30.0)
                                * (1.0 - x2 * (1.0 / 56.0) * (1.0 - x2 * (1.0 / 90.0)))));
        let dsinc =
            x * (-1.0 / 3.0 + x2 * (1.0 / 30.0 - x2 * (1.0 / 840.0 - x2 * (1.0 / 45_360.0))));
        (x * sinc, cos, sinc, dsinc)
    } else {
        let (s, c) = x.sin_cos();
        let sinc = s / x;
        (s, c, sinc, (c - sinc) / x)
    }
}

/// A rod's centre increment over a step of length `dt`, Δc_i = k v_i + (μ_i − μ_{i+1})/h +
/// (k²/2) ĝ, from its joints' multipliers `(μ_i, μ_{i+1})` and `fall` = (k²/2) ĝ: what
/// Newton's residuals and the state's update share.
#[inline(always)]
fn centre_increment(
    dt: f64,
    velocity: Vector2<f64>,
    (multiplier, after): (Vector2<f64>, Vector2<f64>),
    h: f64,
    fall: Vector2<f64>,
) -> Vector2<f64> {
    dt * velocity + (multiplier - after) / h + fall
}

/// The normal n(θ) = (−sin θ, cos θ) of a rod with tangent t = (cos θ, sin θ).
#[inline]
fn normal(t: Vector2<f64>) -> Vector2<f64> {
    Vector2::new(-t.y, t.x)
}

/// One rod's turn Δθ over a step, and what the discrete gradient needs of it.
#[derive(Clone, Copy, Debug)]
struct Turn {
    /// b = sinc(Δθ/2) n(θ + Δθ/2): the angular column of Ḡ, over h/2.
    b: Vector2<f64>,
    /// e(θ + Δθ) − e(θ) = Δθ b = 2 sin(Δθ/2) n(θ + Δθ/2).
    chord: Vector2<f64>,
    /// d(Δθ b)/dΔθ = n(θ + Δθ).
    a: Vector2<f64>,
    /// db/dΔθ.
    db: Vector2<f64>,
}

impl Turn {
    #[inline(always)]
    fn of(tangent: Vector2<f64>, turn: f64) -> Self {
        let half = 0.5 * turn;
        let (s, c, sinc, dsinc) = half_angle(half);
        let n0 = normal(tangent);
        let t_mid = c * tangent + s * n0;
        let n_mid = c * n0 - s * tangent;
        Self {
            b: sinc * n_mid,
            chord: 2.0 * s * n_mid,
            a: c * n_mid - s * t_mid,
            db: 0.5 * (dsinc * n_mid - sinc * t_mid),
        }
    }

    /// b and the chord alone (what the residuals need).
    #[inline(always)]
    fn lean(tangent: Vector2<f64>, turn: f64) -> (Vector2<f64>, Vector2<f64>) {
        let half = 0.5 * turn;
        let (s, c, sinc, _) = half_angle(half);
        let n_mid = c * normal(tangent) - s * tangent;
        (sinc * n_mid, 2.0 * s * n_mid)
    }
}

/// What Newton's Jacobian keeps of a rod between refreshes: a_i / d_i, b_i and 1 / d_i.
#[derive(Clone, Copy, Debug, Default)]
struct Slope {
    a_over_d: Vector2<f64>,
    b: Vector2<f64>,
    inv_d: f64,
}

/// The midpoint rule's state and scratch.
#[derive(Clone, Debug)]
pub struct Midpoint {
    h: f64,
    /// The driver's step k_max.
    k: f64,
    /// The largest rotation of a rod per step (see the module's step control).
    rotation: f64,
    /// Whether the driver's step is coarse ([`Descriptor::is_coarse`]): where the rods'
    /// rotation allows, it is then one step, not a pair (see the module's step control).
    coarse: bool,
    steps: u64,
    /// Rod centres c_i, angles θ_i, unit tangents e(θ_i), velocities v_i, rates ω_i.
    centre: Vec<Vector2<f64>>,
    angle: Vec<f64>,
    tangent: Vec<Vector2<f64>>,
    velocity: Vec<Vector2<f64>>,
    rate: Vec<f64>,
    /// Newton's unknowns: the turns Δθ_i and μ_j = k² λ_j / 2, with μ_N = 0 past the free
    /// end, so that every rod reads the joint at its end, μ_{i+1}, with no case of its own.
    turn: Vec<f64>,
    multiplier: Vec<Vector2<f64>>,
    /// μ/k² of the last two steps taken, and their lengths: the next step's guess
    /// extrapolates them to its own middle.
    recent: Vec<Vector2<f64>>,
    older: Vec<Vector2<f64>>,
    /// Each rod's turn short of its free turn over the last two steps, over k², (k θ̇₀ −
    /// Δθ)/k² = (6/h²) b·(μ_i + μ_{i+1})/k²: the joints' torque, which the next step's guess
    /// extrapolates as it does μ (see [`Midpoint::try_step`]).
    recent_torque: Vec<f64>,
    older_torque: Vec<f64>,
    recent_step: f64,
    older_step: f64,
    /// Per rod in Newton: the Jacobian's a/d, b and 1/d, F_i; per joint: the gap g_j(q₀),
    /// y_j, and the Schur complement's off-diagonal blocks U_j = W_j − I, inverted pivots and
    /// gains D'_j⁻¹ U_j (kept from the first iteration of a step: simplified Newton after it).
    slope: Vec<Slope>,
    residual_angle: Vec<f64>,
    /// Per rod, from a refresh's first pass: a_i = n(θ_i + Δθ_i) and the chord Δθ_i b_i at
    /// the turn the Jacobian is taken at (see [`Midpoint::forward`]).
    end_normal: Vec<Vector2<f64>>,
    turn_chord: Vec<Vector2<f64>>,
    upper: Vec<Matrix2<f64>>,
    gap: Vec<Vector2<f64>>,
    work: Vec<Vector2<f64>>,
    pivot: Vec<Matrix2<f64>>,
    gain: Vec<Matrix2<f64>>,
    /// A = G M⁻¹ Gᵀ at the end of a driver step, for the velocity projection.
    projection: ConstraintMatrix,
    support_tension: f64,
    /// Largest |g_j| and |G v| (before the projection) at the end of the latest driver step.
    residual: f64,
    velocity_residual: f64,
    statistics: StepStatistics,
    /// The energy at the start in the support's frame, which the rescale after each
    /// projection restores, less what the shaken support's frame has taken since.
    energy_start: f64,
    /// The support's motion and the work it has done.
    ledger: SupportLedger,
    /// The time the state is at, within the driver's step.
    clock: f64,
    /// Gravity in the support's frame at the middle of the step being solved.
    gravity: Vector2<f64>,
    observer: ForceSolver,
    /// Steps since the state's velocities were last projected.
    since_projection: u64,
}

impl Midpoint {
    /// The midpoint rule at rest in `scene`, with driver step (largest step) `dt`.
    pub fn new(scene: &Scene, segments: usize, dt: f64) -> Result<Self, ConfigError> {
        scene.validate()?;
        method::validate_segments(&DESCRIPTOR, segments)?;
        method::validate_dt(dt)?;
        let n = segments;
        let angle = scene.initial_angles(n);
        let rate = scene.initial_rates(n);
        let tangent: Vec<_> = angle
            .iter()
            .map(|&theta| geometry::tangent(theta))
            .collect();
        let velocity = geometry::centre_velocities(&tangent, &rate);
        let momentum: f64 = velocity.iter().map(|v| v.x).sum::<f64>() / n as f64;
        let mut midpoint = Self {
            h: 1.0 / n as f64,
            k: dt,
            rotation: ROTATION * DESCRIPTOR.rotation_scale(scene, n, dt),
            coarse: DESCRIPTOR.is_coarse(scene, n, dt),
            steps: 0,
            centre: geometry::centres(&tangent), // eqs. (14)–(15)
            tangent,
            angle,
            velocity,
            rate,
            turn: vec![0.0; n],
            multiplier: vec![Vector2::zeros(); n + 1],
            recent: vec![Vector2::zeros(); n],
            older: vec![Vector2::zeros(); n],
            recent_torque: vec![0.0; n],
            older_torque: vec![0.0; n],
            recent_step: 0.0,
            older_step: 0.0,
            slope: vec![Slope::default(); n],
            upper: vec![Matrix2::zeros(); n],
            residual_angle: vec![0.0; n],
            end_normal: vec![Vector2::zeros(); n],
            turn_chord: vec![Vector2::zeros(); n],
            gap: vec![Vector2::zeros(); n],
            work: vec![Vector2::zeros(); n],
            pivot: vec![Matrix2::zeros(); n],
            gain: vec![Matrix2::zeros(); n],
            projection: ConstraintMatrix::new(n),
            support_tension: 0.0,
            residual: 0.0,
            velocity_residual: 0.0,
            statistics: StepStatistics {
                smallest_step: f64::INFINITY,
                ..StepStatistics::default()
            },
            observer: ForceSolver::new(n),
            energy_start: 0.0,
            ledger: SupportLedger::new(scene.support(), momentum),
            clock: 0.0,
            gravity: Vector2::new(0.0, 1.0),
            since_projection: 0,
        };
        midpoint.energy_start = midpoint.energy_in_frame().total();
        // The joint forces at the start (Newton's own scratch takes the accelerations).
        let observer = &mut midpoint.observer;
        observer.gravity = midpoint.ledger.gravity(0.0);
        observer.solve_at(
            &midpoint.tangent,
            &midpoint.rate,
            &mut midpoint.residual_angle,
        );
        midpoint.support_tension = method::support_tension_at_rest(
            observer.tension_of(0),
            midpoint.angle.first().copied().unwrap_or(0.0),
            n,
        );
        // The first step's guess: μ/k² = f/2 of the joint forces at the start, the nearest
        // known to its middle (for later steps, the last two steps' extrapolated).
        for (recent, force) in midpoint.recent.iter_mut().zip(&observer.force) {
            *recent = 0.5 * force;
        }
        Ok(midpoint)
    }

    /// The energy in the support's frame: Σ h|v|²/2 + Σ (h³/12) ω²/2 − Σ h y (eq. 13 summed).
    fn energy_in_frame(&self) -> Energy {
        let (h, inertia) = (self.h, self.inertia());
        let mut e = Energy::default();
        let rods = self.velocity.iter().zip(&self.rate).zip(&self.centre);
        for ((velocity, rate), centre) in rods {
            e.translational += 0.5 * h * velocity.norm_squared();
            e.rotational += 0.5 * inertia * rate * rate;
            e.potential -= h * centre.y;
        }
        e
    }

    /// The sideways momentum in the support's frame, Σ h v_x.
    fn momentum_x(&self) -> f64 {
        self.h * self.velocity.iter().map(|v| v.x).sum::<f64>()
    }

    /// A rod's moment of inertia about its centre, h³/12.
    fn inertia(&self) -> f64 {
        self.h * self.h * self.h / 12.0
    }

    /// The fastest spin of a rod, max|θ̇_i|.
    fn fastest_spin(&self) -> f64 {
        self.rate.iter().fold(0.0, |m: f64, w| m.max(w.abs()))
    }

    /// The step the state asks for at its fastest spin `spin`: k_max, or shorter where a rod
    /// spins fast.
    fn wanted_step(&self, spin: f64) -> f64 {
        if spin * self.k > self.rotation {
            self.rotation / spin
        } else {
            self.k
        }
    }

    /// The joint gaps g_j(q) = end(rod j−1) − start(rod j) into `gap`.
    fn measure_gaps(&mut self) {
        let half = 0.5 * self.h;
        let mut end_before = Vector2::zeros(); // the support
        let rods = self.centre.iter().zip(&self.tangent);
        for (gap, (centre, tangent)) in self.gap.iter_mut().zip(rods) {
            *gap = end_before - (centre - half * tangent);
            end_before = centre + half * tangent;
        }
    }

    /// Newton's forward pass: every residual at the current (Δθ, μ), and the elimination of
    /// the Schur complement S δμ = r (r_j = h R_j − (h²/2) Σ a_i F_i / d_i). With `refresh`
    /// the Jacobian is evaluated (each rod's part in a pass of its own, before the
    /// elimination) and factorised here; without, the last one serves. Leaves y_j in `work`.
    fn forward(&mut self, dt: f64, refresh: bool) {
        if refresh {
            self.forward_with::<true>(dt);
        } else {
            self.forward_with::<false>(dt);
        }
    }

    /// [`Midpoint::forward`], compiled once with the refresh and once without: one loop
    /// serving both tested which at every rod (`docs/measurements.md`, "The fine rope:
    /// Newton's loops by kind, the shadow's states in batches").
    #[inline(always)]
    fn forward_with<const REFRESH: bool>(&mut self, dt: f64) {
        let (h, half) = (self.h, 0.5 * self.h);
        let spin_gain = 6.0 / (h * h); // (12/h³)(h/2)
        let eye = Matrix2::identity();
        let n = self.angle.len();
        let fall = 0.5 * dt * dt * self.gravity;
        // Every array borrowed once, as a slice of length N: indexed through `self`, each
        // access checked its bound and reloaded the vector's pointer (a quarter of a step's
        // instructions, `valgrind --tool=callgrind`); the arithmetic is the same.
        let Self {
            multiplier,
            tangent,
            turn,
            rate,
            velocity,
            gap,
            upper,
            gain,
            pivot,
            slope,
            work,
            residual_angle,
            end_normal,
            turn_chord,
            ..
        } = self;
        let (multiplier, tangent, turn) = (&multiplier[..=n], &tangent[..n], &turn[..n]);
        let (rate, velocity, gap) = (&rate[..n], &velocity[..n], &gap[..n]);
        let (upper, gain, pivot) = (&mut upper[..n], &mut gain[..n], &mut pivot[..n]);
        let (slope, work) = (&mut slope[..n], &mut work[..n]);
        let residual_angle = &mut residual_angle[..n];
        let (end_normal, turn_chord) = (&mut end_normal[..n], &mut turn_chord[..n]);
        if REFRESH {
            // Each rod's part of the Jacobian first, in a pass of its own: it does not depend
            // on the elimination, yet inside the elimination's loop its division 1/d_i queued
            // with the pivot's, on which the next rod waits (a seventh of a step's samples fell
            // just after the two: docs/measurements.md). The elimination keeps the pivot's.
            for j in 0..n {
                let m = multiplier[j] + multiplier[j + 1];
                let rod = Turn::of(tangent[j], turn[j]);
                let inv_d = 1.0 / (1.0 + spin_gain * rod.db.dot(&m));
                slope[j] = Slope {
                    a_over_d: inv_d * rod.a,
                    b: rod.b,
                    inv_d,
                };
                end_normal[j] = rod.a;
                turn_chord[j] = rod.chord;
            }
        }
        let mut before_increment = Vector2::zeros(); // rod −1: the support does not move
        let mut before_chord = Vector2::zeros();
        let mut before_af = Vector2::zeros(); // a_{j−1} F_{j−1} / d_{j−1}
        let mut before_y = Vector2::zeros();
        let mut passed = Passed::none(); // at a refresh: U_{j−1} D'_{j−1}⁻¹ U_{j−1}
        for j in 0..n {
            let after = multiplier[j + 1];
            let m = multiplier[j] + after;
            let (b, chord) = if REFRESH {
                let Slope { b, inv_d, .. } = slope[j];
                let w = (3.0 * inv_d) * end_normal[j] * b.transpose();
                // S_jj = 2I + W_{j−1} + W_j = 3I + U_{j−1} + W_j.
                let mut diag = if j == 0 {
                    eye + w
                } else {
                    3.0 * eye + upper[j - 1] + w
                };
                if j > 0 {
                    diag -= passed.schur();
                }
                upper[j] = w - eye;
                (pivot[j], gain[j], passed) = eliminate(diag, upper[j], j + 1 == n);
                (b, turn_chord[j])
            } else {
                Turn::lean(tangent[j], turn[j])
            };
            let f = turn[j] - dt * rate[j] + spin_gain * b.dot(&m);
            let af = f * slope[j].a_over_d;
            let increment = centre_increment(dt, velocity[j], (multiplier[j], after), h, fall);
            // R_j = g_j(q₀) + Δc_{j−1} − Δc_j + (h/2)(chord_{j−1} + chord_j).
            let residual = gap[j] + before_increment - increment + half * (before_chord + chord);
            let mut rhs = h * residual - 0.5 * h * h * (before_af + af);
            if j > 0 {
                rhs -= upper[j - 1] * before_y;
            }
            before_y = pivot[j] * rhs;
            work[j] = before_y;
            residual_angle[j] = f;
            (before_increment, before_chord, before_af) = (increment, chord, af);
        }
    }

    /// Newton's backward pass: δμ_j = y_j − gain_j δμ_{j+1}, δθ_i = −(F_i + (6/h²) b_i ·
    /// (δμ_i + δμ_{i+1})) / d_i, both applied. Returns the largest correction.
    fn backward(&mut self) -> f64 {
        let spin_gain = 6.0 / (self.h * self.h);
        let h = self.h;
        let n = self.angle.len();
        let rows = self.work[..n].iter().zip(&self.gain[..n]);
        let rods = self.slope[..n].iter().zip(&self.residual_angle[..n]);
        let unknowns = self.multiplier[..n].iter_mut().zip(&mut self.turn[..n]);
        let mut after = Vector2::zeros(); // δμ_{j+1}
        let (mut largest, mut largest_multiplier): (f64, f64) = (0.0, 0.0);
        for (((y, gain), (slope, f)), (multiplier, turn)) in rows.zip(rods).zip(unknowns).rev() {
            let delta = y - gain * after;
            let correction = -(f + spin_gain * slope.b.dot(&(delta + after))) * slope.inv_d;
            *multiplier += delta;
            *turn += correction;
            largest = largest.max(correction.abs());
            largest_multiplier = largest_multiplier.max(delta.amax());
            after = delta;
        }
        // Divided once: max(a, b)/h is max(a/h, b/h) to the bit.
        largest.max(largest_multiplier / h)
    }

    /// One step of length `dt` from the current state; false if Newton did not converge (the
    /// state is then untouched: Newton moves only Δθ and μ).
    fn try_step(&mut self, dt: f64) -> bool {
        let spin_gain = 6.0 / (self.h * self.h);
        // The frame's gravity at the step's middle: what keeps the balance exact.
        self.gravity = self.ledger.gravity(self.clock + 0.5 * dt);
        // The guess: μ/k² of the last two steps extrapolated linearly to this step's middle
        // (each step's λ belongs to its middle), and the turns from the torque extrapolated
        // likewise (at the first step, from the μ guessed).
        let n = self.angle.len();
        let (k1, k2) = (self.recent_step, self.older_step);
        // (No further than one step's worth: an extrapolation far past its base guesses worse
        // than none.)
        let slope = if k1 > 0.0 && k2 > 0.0 {
            ((dt + k1) / (k1 + k2)).min(1.0)
        } else {
            0.0
        };
        let past = self.recent.iter().zip(&self.older);
        for (multiplier, (recent, older)) in self.multiplier.iter_mut().zip(past) {
            *multiplier = dt * dt * (recent + slope * (recent - older));
        }
        if k1 > 0.0 {
            // The turns from the torque extrapolated: the torque is the small difference of
            // the large forces at a rod's two ends, which the μ guessed carries with a large
            // relative error (from 30° at N = 20, steps of 0.025: turns guessed from μ were
            // first corrected by up to 6e-3 rad, μ/h by 1e-4; from the torque, by 2.5e-3).
            let past = self.recent_torque.iter().zip(&self.older_torque);
            for ((turn, rate), (recent, older)) in self.turn.iter_mut().zip(&self.rate).zip(past) {
                let torque = recent + slope * (recent - older);
                *turn = dt * rate - dt * dt * torque;
            }
        } else {
            for i in 0..n {
                let m = self.multiplier[i] + self.multiplier[i + 1];
                let free = dt * self.rate[i];
                self.turn[i] = free - spin_gain * Turn::lean(self.tangent[i], free).0.dot(&m);
            }
        }
        self.measure_gaps();
        let mut converged = false;
        let mut correction = f64::INFINITY;
        for _ in 0..MAX_ITERATIONS {
            // Simplified Newton (the Jacobian of the first iteration) once close.
            self.forward(dt, correction > REFRESH);
            let before = correction;
            correction = self.backward();
            if !correction.is_finite() {
                break;
            }
            self.statistics.solves += 1;
            // What this correction leaves: about ρ c, ρ = c / c_before its contraction (at
            // the first iteration nothing is known of ρ).
            let left = match before.is_finite() {
                true => correction * (correction / before).min(1.0),
                false => correction,
            };
            if left <= CORRECTION {
                converged = true;
                break;
            }
        }
        if !converged {
            // Nothing of the state has moved; the next guess starts afresh.
            self.recent.iter_mut().for_each(|m| *m = Vector2::zeros());
            (self.recent_step, self.older_step) = (0.0, 0.0);
            return false;
        }
        // v₁ = 2Δq/k − v₀ from the increments; q₁ = q₀ + Δq.
        let two_over = 2.0 / dt;
        let mut moved = 0.0;
        std::mem::swap(&mut self.recent_torque, &mut self.older_torque);
        let per_step = 1.0 / (dt * dt);
        let turns = self.rate.iter().zip(&self.turn);
        for (torque, (rate, turn)) in self.recent_torque.iter_mut().zip(turns) {
            *torque = per_step * (dt * rate - turn);
        }
        let (h, fall) = (self.h, 0.5 * dt * dt * self.gravity);
        let mu = &self.multiplier[..=n];
        let rods = (self.centre.iter_mut().zip(&mut self.velocity))
            .zip(self.angle.iter_mut().zip(&mut self.tangent))
            .zip(self.rate.iter_mut().zip(&self.turn));
        for (i, (((centre, velocity), (angle, tangent)), (rate, &turn))) in rods.enumerate() {
            let joints = (mu[i], mu[i + 1]);
            let increment = centre_increment(dt, *velocity, joints, h, fall);
            moved += increment.x;
            let chord = Turn::lean(*tangent, turn).1;
            *centre += increment;
            *velocity = two_over * increment - *velocity;
            *angle += turn;
            *tangent += chord;
            *rate = two_over * turn - *rate;
        }
        self.ledger.step(self.clock, dt, self.h * moved);
        self.clock += dt;
        // F_0 = −t_0 · f_0, with f_0 = 2μ_0/k² the support's force on rod 0.
        self.support_tension = -2.0 * self.tangent[0].dot(&self.multiplier[0]) / (dt * dt);
        std::mem::swap(&mut self.recent, &mut self.older);
        for (recent, mu) in self.recent.iter_mut().zip(&self.multiplier) {
            *recent = per_step * mu;
        }
        (self.recent_step, self.older_step) = (dt, k1);
        true
    }

    /// One step of the scheme of exactly `dt`, neither split nor followed by the velocity
    /// projection: the bare discrete-gradient map, for checking that it keeps the energy
    /// whatever the sequence of step lengths. The driver's time does not move.
    pub fn step_exactly(&mut self, dt: f64) -> Result<(), Diverged> {
        if self.try_step(dt) {
            Ok(())
        } else {
            Err(self.newton_failed(dt))
        }
    }

    /// After a pair of steps: tangents renormalised, the joint gaps measured, the velocities
    /// projected M-orthogonally onto G(q)v = 0, then scaled so that the energy is the
    /// starting energy again (see the module's note on the velocity constraint).
    fn project(&mut self) {
        let (h, inertia, half) = (self.h, self.inertia(), 0.5 * self.h);
        let n = self.angle.len();
        for t in &mut self.tangent {
            *t *= 1.5 - 0.5 * t.norm_squared(); // one Newton step to |t| = 1
        }
        self.measure_gaps();
        self.residual = self.gap.iter().fold(0.0, |m: f64, g| m.max(g.norm()));
        self.projection.factorise(&self.tangent);
        let mut end_before = Vector2::zeros(); // the support does not move
        let mut largest: f64 = 0.0;
        let rods = self
            .rate
            .iter()
            .zip(&self.velocity)
            .zip(&self.projection.normal);
        for (work, ((rate, velocity), normal)) in self.work.iter_mut().zip(rods) {
            let w = rate * half * normal;
            // d/dt g_j = v_end(j−1) − v_start(j); v_start = v − (h/2) θ̇ n, v_end = v + (h/2) θ̇ n.
            *work = end_before - (velocity - w);
            largest = largest.max(work.norm());
            end_before = velocity + w;
        }
        self.velocity_residual = largest;
        self.projection.forward(h, &mut self.work);
        let mut after = Vector2::zeros(); // ν_{j+1}
        let (mut before, mut projected) = (0.0, 0.0);
        let joints = self.work[..n].iter().zip(&self.projection.gain[..n]);
        // Each rod's velocities are read, then overwritten by their projection, in place.
        let rods = (self.velocity[..n].iter_mut().zip(&mut self.rate[..n]))
            .zip(&self.projection.normal[..n]);
        for ((work, gain), ((velocity, rate), normal)) in joints.zip(rods).rev() {
            let nu = work - gain * after;
            let v = *velocity - (after - nu) / h;
            let w = *rate - half * normal.dot(&(nu + after)) / inertia;
            before += h * velocity.norm_squared() + inertia * *rate * *rate;
            projected += h * v.norm_squared() + inertia * w * w;
            *velocity = v;
            *rate = w;
            after = nu;
        }
        // The kinetic energy the kept energy leaves at this configuration: what the
        // projection removed, and the scheme's round-off since the last projection, go back.
        let potential: f64 = -h * self.centre.iter().map(|c| c.y).sum::<f64>();
        let (before, projected) = (0.5 * before, 0.5 * projected);
        let target = self.energy_start - self.ledger.inertial_work() - potential;
        if projected > 0.0 && (target - projected).abs() <= RESCALE_LIMIT * projected {
            let scale = (target / projected).sqrt();
            self.velocity.iter_mut().for_each(|v| *v *= scale);
            self.rate.iter_mut().for_each(|w| *w *= scale);
            self.statistics.restored_energy += before - projected;
            self.statistics.roundoff_energy += (target - before).abs();
        } else {
            self.statistics.unrestored_energy += (target - projected).abs();
        }
        self.since_projection = 0;
    }

    /// Why a step failed: Newton did not converge even at the shortest step.
    fn newton_failed(&self, dt: f64) -> Diverged {
        Diverged {
            step: self.steps + 1,
            time: (self.steps + 1) as f64 * self.k,
            reason: format!(
                "Newton did not converge even at a step of {dt:.3e} (2^-20 of the largest, \
                 k = {:.3e}; max|θ̇| = {:.3e})",
                self.k,
                self.fastest_spin()
            ),
        }
    }
}

impl Method for Midpoint {
    fn descriptor(&self) -> &'static Descriptor {
        &DESCRIPTOR
    }

    fn segments(&self) -> usize {
        self.angle.len()
    }

    fn dt(&self) -> f64 {
        self.k
    }

    fn steps(&self) -> u64 {
        self.steps
    }

    fn step(&mut self) -> Result<(), Diverged> {
        let mut remaining = self.k;
        let mut ceiling = self.k;
        while remaining > 0.0 {
            let spin = self.fastest_spin();
            self.statistics.fastest_rotation = self.statistics.fastest_rotation.max(spin);
            // The rest of the driver's step in equal steps no longer than the state wants, in
            // pairs, each pair followed by the projection; the last step lands on the
            // driver's time exactly. (After a Newton failure broke a pair, an odd number of
            // steps, the first alone, completes it.)
            let wanted = self.wanted_step(spin).min(ceiling);
            let single = !self.since_projection.is_multiple_of(2);
            let mut parts = (remaining / wanted * (1.0 - 1e-12)).ceil().max(1.0);
            // A coarse driver step the rods allow in one is taken whole, then projected.
            let whole = self.coarse && parts == 1.0 && !single;
            if !whole && (parts % 2.0 == 1.0) != single {
                parts += 1.0;
            }
            let dt = remaining / parts;
            for _ in 0..if single || whole { 1 } else { 2 } {
                if !self.try_step(dt) {
                    self.statistics.newton_failures += 1;
                    ceiling = 0.5 * dt;
                    if ceiling < MIN_STEP_FRACTION * self.k {
                        return Err(self.newton_failed(dt));
                    }
                    break;
                }
                parts -= 1.0;
                remaining = if parts < 0.5 { 0.0 } else { remaining - dt };
                self.since_projection += 1;
                self.statistics.steps += 1;
                self.statistics.smallest_step = self.statistics.smallest_step.min(dt);
            }
            if self.since_projection > 0 && (whole || self.since_projection.is_multiple_of(2)) {
                self.project();
            }
        }
        let values = self.angle.iter().chain(&self.rate);
        let segments = self.segments();
        method::check_finite(
            &DESCRIPTOR,
            segments,
            self.k,
            self.steps,
            values,
            self.support_tension,
        )?;
        self.steps += 1;
        // The driver's time exactly, not the sum of the steps' lengths.
        self.clock = self.time();
        Ok(())
    }

    /// From the method's own velocities (projected onto the joints at the end of every driver
    /// step), in the room.
    fn energy(&self) -> Energy {
        self.ledger
            .in_the_room(self.energy_in_frame(), self.clock, || self.momentum_x())
    }

    fn support(&self) -> Option<SupportNow> {
        self.ledger.now(self.clock, || self.momentum_x())
    }

    fn support_tension(&self) -> f64 {
        self.support_tension
    }

    fn constraint_residual(&self) -> Option<f64> {
        Some(self.residual)
    }

    fn velocity_residual(&self) -> Option<f64> {
        Some(self.velocity_residual)
    }

    fn step_statistics(&self) -> Option<StepStatistics> {
        Some(self.statistics)
    }

    fn angles(&self) -> &[f64] {
        &self.angle
    }

    /// From the tangents the state carries with its angles, without a sine and cosine a rod.
    fn tip(&self) -> geometry::Point {
        geometry::tip_of_tangents(&self.tangent, None)
    }

    fn observe(&mut self, out: &mut Observation) {
        self.observer.gravity = self.ledger.gravity(self.clock);
        self.observer
            .observe(&self.angle, &self.tangent, &self.rate, out);
    }

    fn box_clone(&self) -> Box<dyn Method> {
        Box::new(self.clone())
    }
}
