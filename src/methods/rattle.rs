//! RATTLE on the chain of N uniform rigid rods: the same physical model as `chain` (so second
//! order in h), integrated by a symplectic, time-reversible scheme whose energy error does not
//! drift with a fixed step. (Over thousands of time units it jumps at violent snaps of the
//! free end: docs/measurements.md, "Long runs".)
//!
//! **Coordinates.** Maximal: each rod's centre c_i and angle θ_i, with momenta p_i and L_i.
//! The mass matrix is M = diag(h, h, h³/12) per rod; gravity is (0, h) per rod (y down), and
//! h (−ẍ_s(t), 1) in the frame of a shaken support, each half kick taking it at its own time.
//!
//! **Constraints.** g_j = end(rod j−1) − start(rod j) = 0 for j = 0 … N−1, the "end of rod −1"
//! being the support at the origin: 2N equations. Their Jacobian G has, for joint j, the
//! blocks [I, (h/2) n_{j−1}] on rod j−1 and [−I, (h/2) n_j] on rod j (n the rod's normal), so
//! A = G M⁻¹ Gᵀ is block-tridiagonal with 2×2 blocks, the chain's joint-force system
//! (`constraint_matrix.rs`).
//!
//! **Step** (k; the constraint forces are −Gᵀλ):
//! 1. half kick with gravity, then drift: q̃ = q_n + k M⁻¹ p;
//! 2. find Λ = (k²/2) λ with g(q̃ − M⁻¹ G(q_n)ᵀ Λ) = 0 by simplified Newton, keeping
//!    A(q_n) (factorised once) as the Jacobian;
//! 3. p_{n+½} = M (q_{n+1} − q_n)/k, then the second half kick with gravity;
//! 4. project the velocities on the constraints' tangent space: solve A(q_{n+1}) μ = G M⁻¹ p
//!    and set p −= Gᵀ μ. A(q_{n+1}) is factorised once and serves the next step's Newton too.
//!
//! Each Newton correction is two passes over the rods: the forward elimination, then one
//! backward pass that back-substitutes, moves the rods and measures the new gaps.
//!
//! **Step control, kept reversible.** A step k is split into m equal substeps so that
//! k/m · max|θ̇| ≤ `ROTATION` · min(1, k / k_default) ([`Descriptor::refinement`]) through
//! the whip of the free end: at the default step and above the bound is `ROTATION`, and a
//! finer k tightens it in proportion, so that halving k halves every substep, the whip's too
//! (with a fixed bound the whip's substeps, and its energy error, would not change with k).
//! The rule is symmetric in
//! time: m must satisfy it at *both* ends of the step, so a step that ends faster than it
//! began is retaken with the end's m. Run backwards, the same step picks the same m (Hairer
//! & Söderlind, SIAM J. Sci. Comput. 26, 2005, make the point for variable steps). An integer
//! m is not a smooth step-size function, though: each change of m moves the method to another
//! modified energy, which is where its energy error jumps. A Newton that does not
//! converge retakes the step with twice the substeps, and past `MAX_SUBSTEPS` the step
//! fails as a divergence with its reason.

use super::constraint_matrix::ConstraintMatrix;
use super::joint_forces::ForceSolver;
use super::method::{self, Descriptor, Method, Observation};
use crate::error::{ConfigError, Diverged};
use crate::model::Energy;
use crate::model::geometry;
use crate::model::{Scene, SupportLedger, SupportNow};
use nalgebra::Vector2;

/// C of the estimate k = C h / sqrt(F_max) past which steps split into substeps (Newton
/// slows there); the method never blows up past it, it pays for the substeps.
const COURANT: f64 = 0.4;
/// Largest rotation of a rod per substep, k_sub · max|θ̇|, at the default step and above;
/// a finer step tightens it in proportion (see the step control above).
const ROTATION: f64 = 0.05;
/// Newton stops when every joint closes to this (string lengths).
const TOLERANCE: f64 = 1e-12;
/// Newton iterations before a substep counts as failed.
const MAX_ITERATIONS: usize = 30;
/// A step needing more substeps than this is treated as blown up.
const MAX_SUBSTEPS: u64 = 4096;

/// What RATTLE says of itself (see [`Descriptor`]).
pub const DESCRIPTOR: Descriptor = Descriptor {
    name: "rattle",
    // One rod is a rigid pendulum, two already bend.
    min_segments: 2,
    courant: COURANT,
    limit_meaning: "steps split past about k = C h / sqrt(F_max)",
    past_limit: "past about it each step is split into substeps, so rattle stays stable and only costs more: the limit is where the splitting starts, not where rattle fails",
    keeps_energy: false,
    steady_cost: true,
    blow_up: &[],
    // A fifth of the limit (5e-4 at N = 100): the energy error of the 30° release stays near
    // 2e-6 over 100 time units there, against 1.2e-5 at 1e-3.
    default_step_fraction: 0.2,
    accurate_step: None,
    refuses_unstable_step: false,
    // At the limit its whip from the horizontal errs 17 % more than at the default step
    // (N = 64, `scripts/tolerance-step.sh`): its tolerance keeps the default.
    tolerance_step_fraction: None,
    // `cargo bench --bench step`, N = 1000, before its loops lost their divisions (3 to 12 %
    // less since: docs/measurements.md); left so that `--tolerance` chooses as the committed
    // check measured.
    ns_per_segment_step: 71.0,
    tension_first_at: 0.5,
    discretization: "rods",
    // Two states (centre, angle, tangent and the momenta), the substep's start, A's normals,
    // pivots, off-diagonals and gains, two 2-vector scratches, the observer's joint-force
    // solve, the rates.
    bytes_per_segment: 2 * 64 + 24 + 112 + 2 * 16 + 96 + 8,
    order_in_h: 2,
    colours: ([140, 220, 140], [10, 110, 40]),
    build: |scene, segments, dt| Ok(Box::new(Rattle::new(scene, segments, dt)?)),
    // It starts from any valid scene.
    starts_from: |_| Ok(()),
    plannable: |_, _| true,
};

/// A configuration and its momenta.
#[derive(Clone, Debug)]
struct State {
    /// Rod centres c_i.
    centre: Vec<Vector2<f64>>,
    /// Rod angles θ_i below the horizontal.
    angle: Vec<f64>,
    /// (cos θ_i, sin θ_i), kept with the angle.
    tangent: Vec<Vector2<f64>>,
    /// Linear momenta p_i = h ċ_i.
    momentum: Vec<Vector2<f64>>,
    /// Angular momenta L_i = (h³/12) θ̇_i.
    spin: Vec<f64>,
}

impl State {
    fn copy_from(&mut self, other: &State) {
        self.centre.copy_from_slice(&other.centre);
        self.angle.copy_from_slice(&other.angle);
        self.tangent.copy_from_slice(&other.tangent);
        self.momentum.copy_from_slice(&other.momentum);
        self.spin.copy_from_slice(&other.spin);
    }
}

/// RATTLE's state and scratch.
#[derive(Clone, Debug)]
pub struct Rattle {
    h: f64,
    k: f64,
    /// The largest rotation of a rod per substep (see the module's step control).
    rotation: f64,
    steps: u64,
    now: State,
    /// The state at the start of the step, to retake it from.
    start: State,
    /// The configuration at the start of the substep (for the half-step momenta).
    before_centre: Vec<Vector2<f64>>,
    before_angle: Vec<f64>,
    /// A at the current configuration, factorised.
    matrix: ConstraintMatrix,
    /// Joint gaps g_j, then Newton corrections; joint velocities, then μ.
    work: Vec<Vector2<f64>>,
    /// Λ of the latest substep (the support's entry gives F_0).
    multiplier: Vec<Vector2<f64>>,
    support_tension: f64,
    /// Largest |g_j| after the latest step.
    residual: f64,
    /// For observation: joint forces at the current state, and the angular velocities.
    observer: ForceSolver,
    rate: Vec<f64>,
    /// The support's motion and the work it has done; as at the start of the step, to retake
    /// it from.
    ledger: SupportLedger,
    start_ledger: SupportLedger,
    /// The time the state is at, within the driver's step.
    clock: f64,
}

impl Rattle {
    /// RATTLE at rest in `scene`.
    pub fn new(scene: &Scene, segments: usize, dt: f64) -> Result<Self, ConfigError> {
        scene.validate()?;
        method::validate_segments(&DESCRIPTOR, segments)?;
        method::validate_dt(dt)?;
        let n = segments;
        let angle = scene.initial_angles(n);
        let rate = scene.initial_rates(n);
        let h = 1.0 / n as f64;
        let tangent: Vec<_> = angle
            .iter()
            .map(|&theta| geometry::tangent(theta))
            .collect();
        let momentum: Vec<_> = geometry::centre_velocities(&tangent, &rate)
            .into_iter()
            .map(|v| h * v)
            .collect();
        let ledger = SupportLedger::new(scene.support(), momentum.iter().map(|p| p.x).sum());
        let now = State {
            centre: geometry::centres(&tangent), // eqs. (14)–(15)
            tangent,
            spin: rate.iter().map(|w| h * h * h / 12.0 * w).collect(),
            angle,
            momentum,
        };
        let mut rattle = Self {
            h: 1.0 / n as f64,
            k: dt,
            rotation: ROTATION * DESCRIPTOR.refinement(n, dt),
            steps: 0,
            start: now.clone(),
            before_centre: now.centre.clone(),
            before_angle: now.angle.clone(),
            now,
            matrix: ConstraintMatrix::new(n),
            work: vec![Vector2::zeros(); n],
            multiplier: vec![Vector2::zeros(); n],
            support_tension: 0.0,
            residual: 0.0,
            observer: ForceSolver::new(n),
            rate,
            ledger,
            start_ledger: ledger,
            clock: 0.0,
        };
        rattle.matrix.factorise(&rattle.now.tangent);
        let mut at_rest = Observation::default();
        rattle.observe(&mut at_rest);
        rattle.support_tension = method::support_tension_at_rest(
            at_rest.tension.first().copied().unwrap_or(0.0),
            at_rest.angle.first().copied().unwrap_or(0.0),
            n,
        );
        Ok(rattle)
    }

    /// A rod's moment of inertia about its centre, h³/12.
    fn inertia(&self) -> f64 {
        self.h * self.h * self.h / 12.0
    }

    /// The fastest spin of a rod, max|θ̇_i|.
    fn fastest_spin(&self) -> f64 {
        let largest = self.now.spin.iter().fold(0.0, |m: f64, l| m.max(l.abs()));
        largest / self.inertia()
    }

    /// How many substeps a step needs in the current state (at least one).
    fn substeps(&self) -> u64 {
        let needed = (self.k * self.fastest_spin() / self.rotation).ceil();
        if needed.is_finite() {
            (needed as u64).clamp(1, MAX_SUBSTEPS)
        } else {
            1 // a non-finite state: the step reports it
        }
    }

    /// Step 1: the half kick with gravity (0, h) per rod and the drift q̃ = q_n + dt M⁻¹ p;
    /// the joint gaps g_j = end(rod j−1) − start(rod j) into `work`. Returns the largest.
    fn kick_and_drift(&mut self, dt: f64) -> f64 {
        let (h, inertia, half) = (self.h, self.inertia(), 0.5 * self.h);
        let kick = 0.5 * dt * h * self.ledger.gravity(self.clock);
        let now = &mut self.now;
        let mut end_before = Vector2::zeros(); // the support
        let mut largest: f64 = 0.0;
        // Over zipped slices: no bound checked, no vector's pointer reloaded at each rod.
        let rods = (now.momentum.iter_mut().zip(&mut now.centre))
            .zip(now.angle.iter_mut().zip(&now.spin))
            .zip(&mut now.tangent);
        for (work, (((momentum, centre), (angle, spin)), tangent)) in self.work.iter_mut().zip(rods)
        {
            *momentum += kick;
            *centre += dt / h * *momentum;
            *angle += dt / inertia * spin;
            let (s, c) = angle.sin_cos();
            *tangent = Vector2::new(c, s);
            let gap = end_before - (*centre - half * *tangent);
            largest = largest.max(gap.norm_squared());
            *work = gap;
            end_before = *centre + half * *tangent;
        }
        largest.sqrt()
    }

    /// Step 2, one simplified-Newton correction: solves A(q_n) δ = g, moves the rods by
    /// −M⁻¹ G(q_n)ᵀ δ (rod j carries −δ_j at its start and δ_{j+1} at its end), adds δ to Λ,
    /// and puts the new gaps in `work`. Returns the largest gap.
    fn correct(&mut self) -> f64 {
        let (h, half) = (self.h, 0.5 * self.h);
        // Reciprocals, multiplied by in the loop rather than divided by at every rod (as the
        // midpoint's series are: docs/measurements.md).
        let (per_length, per_inertia) = (1.0 / h, 1.0 / self.inertia());
        self.matrix.forward(h, &mut self.work);
        let n = self.work.len();
        let now = &mut self.now;
        let mut after = Vector2::zeros(); // δ_{j+1}
        let mut largest: f64 = 0.0;
        // From the free end back, over zipped slices; the start of the rod after (moved at
        // the iteration before) carried along, and each joint's gap written one behind.
        let mut start_after = Vector2::zeros();
        let mut gap_after: Option<&mut Vector2<f64>> = None;
        let joints = self.work[..n].iter_mut().zip(&self.matrix.gain[..n]);
        let rods = (self.multiplier[..n]
            .iter_mut()
            .zip(&self.matrix.normal[..n]))
        .zip(now.centre[..n].iter_mut().zip(&mut now.angle[..n]))
        .zip(&mut now.tangent[..n]);
        for ((work, gain), (((multiplier, normal), (centre, angle)), tangent)) in
            joints.zip(rods).rev()
        {
            let delta = *work - gain * after;
            *multiplier += delta;
            *centre -= (after - delta) * per_length;
            let turn = -half * normal.dot(&(delta + after)) * per_inertia;
            *angle += turn;
            *tangent = geometry::turned(*tangent, turn);
            if let Some(gap_after) = gap_after {
                let end = *centre + half * *tangent;
                let gap = end - start_after;
                largest = largest.max(gap.norm_squared());
                *gap_after = gap;
            }
            start_after = *centre - half * *tangent;
            gap_after = Some(work);
            after = delta;
        }
        let gap = -start_after;
        self.work[0] = gap;
        largest.max(gap.norm_squared()).sqrt()
    }

    /// One RATTLE substep of length `dt`; false if Newton did not converge. `self.matrix`
    /// holds A at the current configuration on entry, and at the new one on exit.
    fn substep(&mut self, dt: f64) -> bool {
        let (h, inertia) = (self.h, self.inertia());
        self.before_centre.copy_from_slice(&self.now.centre);
        self.before_angle.copy_from_slice(&self.now.angle);
        self.multiplier
            .iter_mut()
            .for_each(|m| *m = Vector2::zeros());
        let mut gap = self.kick_and_drift(dt);
        let mut iterations = 0;
        while gap >= TOLERANCE || gap.is_nan() {
            if !gap.is_finite() || iterations == MAX_ITERATIONS {
                return false;
            }
            gap = self.correct();
            iterations += 1;
        }
        self.residual = gap;
        // F_0 = −t_0 · f_0, with f_0 = 2Λ_0/dt² the support's force on rod 0 (t at q_n).
        let n0 = self.matrix.normal[0];
        let along = Vector2::new(n0.y, -n0.x).dot(&self.multiplier[0]);
        self.support_tension = -2.0 * along / (dt * dt);
        // 3. Momenta at the half step from the positions, then the second half kick.
        let kick = 0.5 * dt * h * self.ledger.gravity(self.clock + dt);
        let now = &mut self.now;
        let mut moved = 0.0;
        let (mass_rate, inertia_rate) = (h / dt, inertia / dt);
        let before = self.before_centre.iter().zip(&self.before_angle);
        let rods =
            (now.centre.iter().zip(&now.angle)).zip(now.momentum.iter_mut().zip(&mut now.spin));
        for (((centre, angle), (momentum, spin)), (centre_before, angle_before)) in rods.zip(before)
        {
            let shift = centre - centre_before;
            moved += shift.x;
            *momentum = mass_rate * shift + kick;
            *spin = inertia_rate * (angle - angle_before);
        }
        self.ledger.step(self.clock, dt, h * moved);
        self.clock += dt;
        // 4. Project the velocities with A at the new configuration.
        self.matrix.factorise(&self.now.tangent);
        self.project_velocities();
        true
    }

    /// p −= Gᵀ μ with A μ = G M⁻¹ p: the joints' relative velocities become zero.
    fn project_velocities(&mut self) {
        let (h, half) = (self.h, 0.5 * self.h);
        let (per_length, per_inertia) = (1.0 / h, 1.0 / self.inertia());
        let now = &mut self.now;
        let mut end_before = Vector2::zeros(); // the support does not move
        let rods = now.momentum.iter().zip(&now.spin).zip(&self.matrix.normal);
        for (work, ((momentum, spin), normal)) in self.work.iter_mut().zip(rods) {
            let v = momentum * per_length;
            let w = spin * per_inertia * half * normal;
            // d/dt g_j = v_end(j−1) − v_start(j); v_start = v − (h/2) θ̇ n, v_end = v + (h/2) θ̇ n.
            *work = end_before - (v - w);
            end_before = v + w;
        }
        self.matrix.forward(h, &mut self.work);
        let mut after = Vector2::zeros(); // μ_{j+1}
        let n = self.work.len();
        let joints = self.work[..n].iter().zip(&self.matrix.gain[..n]);
        let rods =
            (now.momentum[..n].iter_mut().zip(&mut now.spin[..n])).zip(&self.matrix.normal[..n]);
        for ((work, gain), ((momentum, spin), normal)) in joints.zip(rods).rev() {
            let mu = work - gain * after;
            *momentum -= after - mu;
            *spin -= half * normal.dot(&(mu + after));
            after = mu;
        }
    }

    /// Goes back to the state at the start of the step (and A there).
    fn restart(&mut self) {
        self.now.copy_from(&self.start);
        self.ledger = self.start_ledger;
        self.clock = self.time();
        self.matrix.factorise(&self.now.tangent);
    }

    /// The sideways momentum in the support's frame, Σ p_x.
    fn momentum_x(&self) -> f64 {
        self.now.momentum.iter().map(|p| p.x).sum()
    }

    /// Why a step failed: Newton could not close the joints even in the finest substeps.
    fn newton_failed(&self) -> Diverged {
        let hint = method::stability_hint(&DESCRIPTOR, self.segments(), self.k);
        Diverged {
            step: self.steps + 1,
            time: (self.steps + 1) as f64 * self.k,
            reason: format!(
                "the joints could not be closed: Newton did not converge even in \
                 {MAX_SUBSTEPS} substeps (k · max|θ̇| = {:.3} at the step's start; {hint})",
                self.k * self.fastest_spin()
            ),
        }
    }
}

impl Method for Rattle {
    fn descriptor(&self) -> &'static Descriptor {
        &DESCRIPTOR
    }

    fn segments(&self) -> usize {
        self.now.angle.len()
    }

    fn dt(&self) -> f64 {
        self.k
    }

    fn steps(&self) -> u64 {
        self.steps
    }

    fn step(&mut self) -> Result<(), Diverged> {
        self.start.copy_from(&self.now);
        self.start_ledger = self.ledger;
        let mut substeps = self.substeps();
        loop {
            let dt = self.k / substeps as f64;
            let retry = if (0..substeps).all(|_| self.substep(dt)) {
                // The same rule at the end of the step: what the step would pick run
                // backwards from there (the symmetric choice).
                let at_end = self.substeps();
                if at_end <= substeps {
                    break;
                }
                at_end
            } else {
                2 * substeps
            };
            self.restart();
            substeps = retry;
            if substeps > MAX_SUBSTEPS {
                return Err(self.newton_failed());
            }
        }
        let values = self.now.angle.iter().chain(&self.now.spin);
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
        // The driver's time exactly, not the sum of the substeps' lengths.
        self.clock = self.time();
        Ok(())
    }

    /// From the method's own momenta: Σ |p|²/2h + Σ L²/(2 h³/12) − Σ h y (eq. 13 summed), in
    /// the room.
    fn energy(&self) -> Energy {
        let (h, inertia) = (self.h, self.inertia());
        let mut e = Energy::default();
        for i in 0..self.now.angle.len() {
            e.translational += self.now.momentum[i].norm_squared() / (2.0 * h);
            e.rotational += self.now.spin[i] * self.now.spin[i] / (2.0 * inertia);
            e.potential -= h * self.now.centre[i].y;
        }
        self.ledger.in_the_room(e, self.clock, || self.momentum_x())
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

    fn angles(&self) -> &[f64] {
        &self.now.angle
    }

    /// From the tangents the state carries with its angles, without a sine and cosine a rod.
    fn tip(&self) -> geometry::Point {
        geometry::tip_of_tangents(&self.now.tangent, None)
    }

    fn observe(&mut self, out: &mut Observation) {
        self.observer.gravity = self.ledger.gravity(self.clock);
        let inertia = self.inertia();
        for (rate, spin) in self.rate.iter_mut().zip(&self.now.spin) {
            *rate = spin / inertia;
        }
        let now = &self.now;
        self.observer
            .observe(&now.angle, &now.tangent, &self.rate, out);
    }

    fn box_clone(&self) -> Box<dyn Method> {
        Box::new(self.clone())
    }
}
