//! A chain of N uniform rigid rods hinged at the support: the discrete model the report's own
//! energy (eq. 13) already assumes, integrated exactly as a multibody system.
//!
//! Rod i (mass m = h, length h, moment of inertia m h²/12 about its centre) feels the joint
//! force f_i at its start, −f_{i+1} at its end (f_N = 0, free tip) and gravity. Newton–Euler
//! for each rod plus the condition that neighbouring rods share their joint gives, for the
//! unknown joint forces, a symmetric positive-definite block-tridiagonal system with 2×2
//! blocks (P_i = n_i n_iᵀ the projector on the rod's normal n_i = (−sin φ_i, cos φ_i)):
//!
//! * support, j = 0:  (I + 3P_0) f_0 + (3P_0 − I) f_1 = −m ŷ − (m h/2) φ̇_0² t_0
//! * joint j ≥ 1:     (3P_{j−1} − I) f_{j−1} + (2I + 3P_{j−1} + 3P_j) f_j + (3P_j − I) f_{j+1}
//!   = −(m h/2) (φ̇_{j−1}² t_{j−1} + φ̇_j² t_j)
//!
//! (ŷ: gravity; in the frame of a shaken support, (−ẍ_s(t), 1), evaluated at each RK4 stage's
//! time) solved by block Thomas in O(N); then φ̈_i = −(6/(m h)) n_i · (f_i + f_{i+1}). Time: classical
//! RK4 in (φ, φ̇). No division by the tension anywhere, so it starts from the horizontal;
//! inextensibility is exact by construction; the rods converge to the continuum at O(h²).

use super::joint_forces::ForceSolver;
use super::method::{self, Descriptor, Method, Observation};
use crate::error::{ConfigError, Diverged};
use crate::model::energy::{self, Energy};
use crate::model::geometry;
use crate::model::{Scene, SupportLedger, SupportNow};
use nalgebra::Vector2;

/// Substep bounds: k_sub ≤ C_F h / sqrt(F_max) (measured stable up to C_F ≈ 0.6 at N = 100)
/// and k_sub |φ̇|_max ≤ C_ω, at the default step and above; a finer step tightens both in
/// proportion ([`Descriptor::refinement`]), so that it refines the whip as much as the rest.
/// Past twice the tolerance step C_ω alone loosens with the step, at most tenfold
/// ([`Descriptor::rotation_scale`]); C_F, which keeps RK4 stable, never does.
const SUBSTEP_COURANT: f64 = 0.4;
const SUBSTEP_ROTATION: f64 = 0.02;
/// A state needing more substeps than this per step is treated as blown up.
const MAX_SUBSTEPS: u64 = 100_000;

/// What the chain says of itself (see [`Descriptor`]).
pub const DESCRIPTOR: Descriptor = Descriptor {
    name: "chain",
    // One rod is a rigid pendulum, two already bend.
    min_segments: 2,
    // Past this the chain still runs (it substeps to stay stable) but pays for the substeps.
    courant: SUBSTEP_COURANT,
    limit_meaning: "substeps start: k = C h / sqrt(F_max)",
    past_limit: "past it each step is split into RK4 substeps within it, so the chain stays stable and only costs more: the limit is where the substeps start, not where the chain fails",
    keeps_energy: false,
    steady_cost: true,
    blow_up: &[],
    // 0.3 of the limit (5e-4 at N = 100): RK4's energy loss stays below 1e-6 over 10 time
    // units there (tests/chain_physics.rs); the state adds substeps where the whip needs them.
    default_step_fraction: 0.3,
    accurate_step: None,
    refuses_unstable_step: false,
    // The limit itself, where substeps start (the state adds them where the whip needs them):
    // the worst tip error to t = 3 within 2.3 % of the default step's in every scene and N
    // probed, with 3.3 times fewer steps (`scripts/tolerance-step.sh`).
    tolerance_step_fraction: Some(1.0),
    // `cargo bench --bench step`, N = 1000, before two later cuts of its step (its solve's
    // blocks written out; its rods turned between steps: docs/measurements.md); left so that
    // `--tolerance` chooses as the committed check measured.
    ns_per_segment_step: 170.0,
    tension_first_at: 0.5,
    discretization: "rods",
    // Seven f64 vectors of RK4, and the joint-force solve's 2×2 gain and four 2-vectors.
    bytes_per_segment: 7 * 8 + 4 * 8 + 4 * 16,
    order_in_h: 2,
    colours: ([110, 170, 240], [10, 40, 140]),
    build: |scene, segments, dt| Ok(Box::new(Chain::new(scene, segments, dt)?)),
    // Equal rods start from any valid scene.
    starts_from: |_| Ok(()),
    plannable: |_, _| true,
};

/// Where a solve puts the rods: at angles φ (which become the base of the step's later
/// stages), or at the last such angles turned by a turn each (an RK4 stage's, φ + a φ̇).
#[derive(Clone, Copy)]
enum Rods<'a> {
    At(&'a [f64]),
    Turned(&'a [f64]),
}

/// The chain's state and RK4 scratch.
#[derive(Clone, Debug)]
pub struct Chain {
    /// The chain's own, or the graded rods' ([`super::graded`]).
    descriptor: &'static Descriptor,
    k: f64,
    /// What the substep bounds are multiplied by ([`Descriptor::refinement`]).
    refinement: f64,
    /// What the rotation bound alone is multiplied by ([`Descriptor::rotation_scale`]).
    rotation_scale: f64,
    steps: u64,
    phi: Vec<f64>,
    omega: Vec<f64>,
    /// An RK4 stage's angles less the step's: φ_stage − φ.
    stage_turn: Vec<f64>,
    stage_omega: Vec<f64>,
    sum_phi: Vec<f64>,
    sum_omega: Vec<f64>,
    alpha: Vec<f64>,
    solver: ForceSolver,
    support_tension: f64,
    /// Rod lengths where they are graded ([`Chain::graded`]); `None` for N equal rods.
    length: Option<Vec<f64>>,
    /// The support's motion and the work it has done.
    ledger: SupportLedger,
}

/// Rods graded along the string start from a release only: a release is straight, so every
/// rod starts at its angle whatever its length. [`Chain::graded`] refuses other scenes
/// whatever descriptor it answers as, and the graded method's `starts_from` is this.
pub(crate) fn graded_starts_from(scene: &Scene) -> Result<(), ConfigError> {
    match scene {
        Scene::Release { .. } => Ok(()),
        _ => Err(ConfigError::GradedScene(scene.name())),
    }
}

impl Chain {
    /// The chain at rest in `scene`.
    pub fn new(scene: &Scene, segments: usize, dt: f64) -> Result<Self, ConfigError> {
        scene.validate()?;
        method::validate_segments(&DESCRIPTOR, segments)?;
        method::validate_dt(dt)?;
        let n = segments;
        let (phi, omega) = (scene.initial_angles(n), scene.initial_rates(n));
        let ledger = SupportLedger::new(scene.support(), geometry::momentum(&phi, &omega).x);
        let mut chain = Self {
            descriptor: &DESCRIPTOR,
            k: dt,
            refinement: DESCRIPTOR.refinement(n, dt),
            rotation_scale: DESCRIPTOR.rotation_scale(scene, n, dt),
            steps: 0,
            phi,
            omega,
            stage_turn: vec![0.0; n],
            stage_omega: vec![0.0; n],
            sum_phi: vec![0.0; n],
            sum_omega: vec![0.0; n],
            alpha: vec![0.0; n],
            solver: ForceSolver::new(n),
            support_tension: 0.0,
            length: None,
            ledger,
        };
        chain.evaluate_now();
        Ok(chain)
    }

    /// The chain of `segments` rods graded towards the free end, rod i spanning
    /// s_i = 1 − (1 − i/N)^`exponent` to s_{i+1} (the last rod about `exponent` N^−`exponent` long),
    /// at rest in `scene` (a release: every rod at its angle), answering as `descriptor` says
    /// (the graded method's, [`super::graded`]; the examples that measure other exponents
    /// borrow it).
    pub fn graded(
        descriptor: &'static Descriptor,
        scene: &Scene,
        segments: usize,
        dt: f64,
        exponent: f64,
    ) -> Result<Self, ConfigError> {
        graded_starts_from(scene)?;
        let mut chain = Self::new(scene, segments, dt)?;
        chain.descriptor = descriptor;
        chain.refinement = descriptor.refinement(segments, dt);
        chain.rotation_scale = descriptor.rotation_scale(scene, segments, dt);
        let n = segments as f64;
        let edge = |i: usize| 1.0 - (1.0 - i as f64 / n).powf(exponent);
        let length: Vec<f64> = (0..segments).map(|i| edge(i + 1) - edge(i)).collect();
        // Each rod at the scene's angle at its middle (a release's are all one angle).
        chain.length = Some(length);
        chain.evaluate_now();
        Ok(chain)
    }

    /// The sideways momentum in the support's frame.
    fn momentum_x(&self) -> f64 {
        geometry::momentum_of(&self.phi, &self.omega, self.length.as_deref()).x
    }

    /// The joint forces and angular accelerations with the rods at `rods` and rates `omega`
    /// under `gravity` (the support's frame's, [`SupportLedger::gravity`]) into `alpha`.
    fn solve(
        solver: &mut ForceSolver,
        length: Option<&[f64]>,
        gravity: Vector2<f64>,
        rods: Rods,
        omega: &[f64],
        alpha: &mut [f64],
    ) -> (f64, f64) {
        solver.gravity = gravity;
        match rods {
            Rods::At(phi) => solver.orient_moved(phi),
            Rods::Turned(turn) => solver.orient_turned(turn),
        }
        solver.solve(omega, length, alpha)
    }

    /// Accelerations and forces at the current state; returns the largest joint force and
    /// the largest |φ̇|.
    fn evaluate_now(&mut self) -> (f64, f64) {
        let gravity = self.ledger.gravity(self.time());
        let extremes = Self::solve(
            &mut self.solver,
            self.length.as_deref(),
            gravity,
            Rods::At(&self.phi),
            &self.omega,
            &mut self.alpha,
        );
        self.support_tension = -self.solver.tangent[0].dot(&self.solver.force[0]);
        extremes
    }

    /// How many RK4 substeps the outer step k needs in a state with joint forces up to
    /// `force` and rates up to `rate`: the fastest wave, sqrt(F)/h, and the fastest spin
    /// must each be resolved (k_sub ≤ C_F h / sqrt(F) and k_sub ≤ C_ω / |φ̇|).
    fn substeps(&self, force: f64, rate: f64) -> u64 {
        let h = 1.0 / self.phi.len() as f64;
        // The fastest wave across a rod, sqrt(F)/h: equal rods take the largest force, graded
        // ones each rod's own (the short end rods carry little).
        let wave = match &self.length {
            None => self.k * force.max(1e-12).sqrt() / (SUBSTEP_COURANT * self.refinement * h),
            Some(length) => {
                let fastest = self
                    .solver
                    .force
                    .iter()
                    .zip(length)
                    .map(|(f, l)| f.norm().max(1e-12).sqrt() / l)
                    .fold(0.0, f64::max);
                self.k * fastest / (SUBSTEP_COURANT * self.refinement)
            }
        };
        let spin = self.k * rate / (SUBSTEP_ROTATION * self.rotation_scale);
        let needed = wave.max(spin).ceil();
        if needed.is_finite() {
            (needed as u64).clamp(1, MAX_SUBSTEPS)
        } else {
            1 // a non-finite state: the step reports it
        }
    }

    /// One classical RK4 step of size `dt` from (φ, φ̇) at time `start`, with stage-1
    /// accelerations already in `self.alpha` (and the solver oriented at φ). Each later
    /// stage's angles are φ plus a turn, `stage_turn`, which the solver applies as a rotation
    /// of the rods at φ.
    fn rk4(&mut self, start: f64, dt: f64) {
        // The loops run over zipped slices, not indices: so they carry no bounds checks and
        // vectorise however the compiler inlines this (indexed, they lost both once `step`
        // took `Chain::solve` in, and a step ran about a tenth slower: docs/measurements.md).
        let (half, sixth) = (0.5 * dt, dt / 6.0);
        let stages = self.stage_turn.iter_mut().zip(&mut self.stage_omega);
        let sums = self.sum_phi.iter_mut().zip(&mut self.sum_omega);
        let now = self.omega.iter().zip(&self.alpha);
        for (((turn, stage_omega), (sum_phi, sum_omega)), (&w, &a)) in stages.zip(sums).zip(now) {
            (*sum_phi, *sum_omega) = (w, a);
            (*turn, *stage_omega) = (half * w, w + half * a);
        }
        // Each stage's time, then its weight and how far the next stage advances.
        for (at, weight, advance) in [(0.5, 2.0, 0.5 * dt), (0.5, 2.0, dt), (1.0, 1.0, 0.0)] {
            Self::solve(
                &mut self.solver,
                self.length.as_deref(),
                self.ledger.gravity(start + at * dt),
                Rods::Turned(&self.stage_turn),
                &self.stage_omega,
                &mut self.alpha,
            );
            let stages = self.stage_turn.iter_mut().zip(&mut self.stage_omega);
            let sums = self.sum_phi.iter_mut().zip(&mut self.sum_omega);
            let now = self.omega.iter().zip(&self.alpha);
            for (((turn, stage_omega), (sum_phi, sum_omega)), (&omega, &a)) in
                stages.zip(sums).zip(now)
            {
                let w = *stage_omega;
                *sum_phi += weight * w;
                *sum_omega += weight * a;
                (*turn, *stage_omega) = (advance * w, omega + advance * a);
            }
        }
        let state = self.phi.iter_mut().zip(&mut self.omega);
        for ((phi, omega), (&sum_phi, &sum_omega)) in
            state.zip(self.sum_phi.iter().zip(&self.sum_omega))
        {
            *phi += sixth * sum_phi;
            *omega += sixth * sum_omega;
        }
    }
}

impl Method for Chain {
    fn descriptor(&self) -> &'static Descriptor {
        self.descriptor
    }

    fn segments(&self) -> usize {
        self.phi.len()
    }

    fn dt(&self) -> f64 {
        self.k
    }

    fn steps(&self) -> u64 {
        self.steps
    }

    fn step(&mut self) -> Result<(), Diverged> {
        let k = self.k;
        let n = self.phi.len();
        // Stage 1 at the current state; its forces and rates also say how many substeps the
        // state needs (the whip of a falling string needs many, a gentle swing one).
        let (force, rate) = self.evaluate_now();
        let substeps = self.substeps(force, rate);
        let dt = k / substeps as f64;
        // The first moment's sideways part, for the support's work: only where it moves, and
        // each substep's end is the next one's start.
        let moves = self.ledger.moves();
        let mut moment = if moves {
            geometry::first_moment(&self.phi).x
        } else {
            0.0
        };
        for sub in 0..substeps {
            let start = self.time() + sub as f64 * dt;
            if sub > 0 {
                Self::solve(
                    &mut self.solver,
                    self.length.as_deref(),
                    self.ledger.gravity(start),
                    Rods::At(&self.phi),
                    &self.omega,
                    &mut self.alpha,
                );
            }
            self.rk4(start, dt);
            if moves {
                let after = geometry::first_moment(&self.phi).x;
                self.ledger.step(start, dt, after - moment);
                moment = after;
            }
        }
        let check: f64 = self.phi.iter().chain(&self.omega).sum();
        if !(check.is_finite() && self.support_tension.is_finite()) {
            return Err(method::non_finite(
                self.descriptor,
                n,
                k,
                self.steps,
                "the angle or the joint force",
            ));
        }
        self.steps += 1;
        // Oriented at the new angles now rather than at the next step's start (which then
        // finds them so): the tip the live estimate reads at this step comes from them.
        self.solver.orient_moved(&self.phi);
        Ok(())
    }

    /// From the tangents the step oriented at its new angles, where they are at these.
    fn tip(&self) -> geometry::Point {
        let lengths = self.lengths();
        match self.solver.tangents_at(&self.phi) {
            Some(tangents) => geometry::tip_of_tangents(tangents, lengths),
            None => geometry::tip_of(&self.phi, lengths),
        }
    }

    /// From the tangents the step oriented at its new angles, as the tip: the run watches
    /// the energy at every step.
    fn energy(&self) -> Energy {
        let in_frame = match (self.solver.tangents_at(&self.phi), &self.length) {
            (Some(tangents), lengths) => {
                energy::energy_of_tangents(tangents, &self.omega, lengths.as_deref())
            }
            (None, None) => energy::energy(&self.phi, &self.omega),
            (None, Some(length)) => {
                energy::energy_of_rods(self.phi.len(), |i| (self.phi[i], self.omega[i], length[i]))
            }
        };
        self.ledger
            .in_the_room(in_frame, self.time(), || self.momentum_x())
    }

    fn support(&self) -> Option<SupportNow> {
        self.ledger.now(self.time(), || self.momentum_x())
    }

    fn support_tension(&self) -> f64 {
        self.support_tension
    }

    fn angles(&self) -> &[f64] {
        &self.phi
    }

    fn lengths(&self) -> Option<&[f64]> {
        self.length.as_deref()
    }

    fn observe(&mut self, out: &mut Observation) {
        self.evaluate_now();
        out.angle.clone_from(&self.phi);
        // Its tangents may be turned rather than worked out (`ForceSolver::orient_moved`):
        // a frame works them out from the angles.
        out.tangent.clear();
        out.angular_velocity.clone_from(&self.omega);
        out.angular_acceleration.clone_from(&self.alpha);
        self.solver.tension(&mut out.tension);
    }

    fn box_clone(&self) -> Box<dyn Method> {
        Box::new(self.clone())
    }
}
