//! The report's finite-difference scheme (the "seed scheme"), with the support condition's
//! sign as it follows from eq. (9).
//!
//! State: φ at t and t − k (and t − 2k, kept for free by rotating buffers, for accelerations).
//! Each step: (i) the tension F(t) from the tridiagonal system (3)+(5) with F_{N−1} = 0, by a
//! Thomas sweep; (ii) the interior update (8), fused with the back-substitution so that the
//! step reads the arrays twice; (iii) the support condition (11); (iv) the free end (12).

use super::method::{self, BlowUp, Descriptor, Method, Observation};
use crate::error::{ConfigError, Diverged};
use crate::model::Scene;
use crate::model::energy::{self, Energy};

/// What the seed scheme says of itself (see [`Descriptor`]).
pub const DESCRIPTOR: Descriptor = Descriptor {
    name: "seed",
    // (11) reaches φ_2 and (12) φ_{N−3}, and both must be interior segments updated by (8).
    min_segments: 4,
    // Measured by `rope study` (its stability map): the scheme blows up past about this.
    courant: 0.7,
    limit_meaning: "estimate k = C h / sqrt(F_max)",
    past_limit: "the scheme blows up past it, so a step past it is refused unless --allow-unstable asks to watch it fail",
    keeps_energy: false,
    steady_cost: true,
    // `rope study --blow-up 200 --out assets/blow-up`: every run diverged before t = 200.
    blow_up: &[
        BlowUp {
            segments: 25,
            earliest: 18.2,
            latest: 132.3,
        },
        BlowUp {
            segments: 50,
            earliest: 23.6,
            latest: 74.1,
        },
        BlowUp {
            segments: 100,
            earliest: 21.0,
            latest: 62.8,
        },
        BlowUp {
            segments: 200,
            earliest: 17.7,
            latest: 66.5,
        },
        BlowUp {
            segments: 400,
            earliest: 6.4,
            latest: 8.2,
        },
    ],
    // Half the limit: the error is dominated by the first order in h, a smaller k buys
    // nothing.
    default_step_fraction: 0.5,
    accurate_step: None,
    refuses_unstable_step: true,
    // The scheme blows up past its limit: its tolerance runs at the default step.
    tolerance_step_fraction: None,
    ns_per_segment_step: 10.2,
    tension_first_at: 1.0,
    discretization: "finite differences",
    // φ at three times, the tension, and the sweep's two scratch vectors.
    bytes_per_segment: 6 * 8,
    order_in_h: 1,
    colours: ([250, 170, 60], [150, 30, 0]),
    build: |scene, segments, dt| Ok(Box::new(Seed::new(scene, segments, dt)?)),
    starts_from,
    plannable: |_, _| true,
};

/// Which sign the support condition (11) is used with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SupportSign {
    /// φ_0 = φ_2 + 2 (h/F_0) cos φ_1: what eq. (9) gives. The scheme as it should be.
    Derived,
    /// φ_0 = φ_2 − 2 (h/F_0) cos φ_1: the report's printed (10)–(11). Blows up; kept so that
    /// a test can show it.
    Printed,
}

/// The seed scheme's state.
#[derive(Clone, Debug)]
pub struct Seed {
    h: f64,
    k: f64,
    steps: u64,
    sign: f64,
    /// φ(t)
    phi: Vec<f64>,
    /// φ(t − k)
    prev: Vec<f64>,
    /// φ(t − 2k); each step writes φ(t + k) here, then the three rotate.
    prev2: Vec<f64>,
    /// F_i from the latest solve; F_{N−1} = 0.
    tension: Vec<f64>,
    /// Thomas sweep scratch: modified upper diagonal and right-hand side.
    sweep_c: Vec<f64>,
    sweep_d: Vec<f64>,
}

/// The scenes the report's scheme cannot start from: the horizontal (its support condition
/// (11) divides by the support tension sin φ₀, zero there), a fold (its free arm falls with
/// no tension, and the scheme diverges) and a shaken support (no term of it moves the support).
fn starts_from(scene: &Scene) -> Result<(), ConfigError> {
    if scene.support_angle() == 0.0 {
        return Err(ConfigError::SeedFromHorizontal);
    }
    match scene {
        Scene::Fold { .. } => Err(ConfigError::SeedFold),
        Scene::Shake { .. } => Err(ConfigError::SeedShake),
        Scene::Release { .. } | Scene::Mode { .. } => Ok(()),
    }
}

impl Seed {
    /// The scheme at rest in `scene`, with the derived support sign.
    pub fn new(scene: &Scene, segments: usize, dt: f64) -> Result<Self, ConfigError> {
        Self::with_support_sign(scene, segments, dt, SupportSign::Derived)
    }

    /// As [`Seed::new`], choosing the sign of the support condition (11).
    pub fn with_support_sign(
        scene: &Scene,
        segments: usize,
        dt: f64,
        sign: SupportSign,
    ) -> Result<Self, ConfigError> {
        scene.validate()?;
        method::validate_segments(&DESCRIPTOR, segments)?;
        method::validate_dt(dt)?;
        starts_from(scene)?;
        let phi = scene.initial_angles(segments);
        let mut seed = Self {
            h: 1.0 / segments as f64,
            k: dt,
            steps: 0,
            sign: match sign {
                SupportSign::Derived => 1.0,
                SupportSign::Printed => -1.0,
            },
            prev: phi.clone(), // at rest: φ(t − k) = φ(t)
            prev2: phi.clone(),
            phi,
            tension: vec![0.0; segments],
            sweep_c: vec![0.0; segments],
            sweep_d: vec![0.0; segments],
        };
        seed.solve_tension();
        Ok(seed)
    }

    /// The tension profile of the latest solve, F_0 … F_{N−1}.
    pub fn tension(&self) -> &[f64] {
        &self.tension
    }

    /// The forward Thomas sweep of the tension system at time t: eq. (5) as row 0,
    /// eq. (3) for rows 1 … N−2, with F_{N−1} = 0. Leaves the modified coefficients in the
    /// sweep scratch; the back-substitution is F_i = d_i − c_i F_{i+1}.
    #[inline]
    fn forward_sweep(&mut self) {
        let n = self.phi.len();
        let (h, inv_k) = (self.h, 1.0 / self.k);
        let (phi, prev) = (&self.phi[..], &self.prev[..n]);
        let (c, d) = (&mut self.sweep_c[..n], &mut self.sweep_d[..n]);
        // Row 0, eq. (5): F_1 − F_0 = −h sin φ_0, i.e. diagonal −1, upper 1.
        c[0] = -1.0;
        d[0] = h * phi[0].sin();
        for i in 1..n - 1 {
            let dphi = phi[i + 1] - phi[i - 1];
            let rate = (phi[i] - prev[i]) * inv_k;
            // eq. (3): F_{i−1} + (−2 − (φ_{i+1} − φ_{i−1})²/4) F_i + F_{i+1} = −h² φ̇_i²
            let diag = -2.0 - 0.25 * dphi * dphi;
            let rhs = -h * h * rate * rate;
            let inv = 1.0 / (diag - c[i - 1]);
            c[i] = inv;
            d[i] = (rhs - d[i - 1]) * inv;
        }
    }

    /// Solves the tension at the current time into `self.tension`.
    fn solve_tension(&mut self) {
        self.forward_sweep();
        let n = self.phi.len();
        let f = &mut self.tension;
        f[n - 1] = 0.0;
        let mut next = 0.0;
        for i in (0..n - 1).rev() {
            next = self.sweep_d[i] - self.sweep_c[i] * next;
            f[i] = next;
        }
    }

    fn diverged(&self, what: &str) -> Diverged {
        method::non_finite(&DESCRIPTOR, self.phi.len(), self.k, self.steps, what)
    }
}

impl Method for Seed {
    fn descriptor(&self) -> &'static Descriptor {
        &DESCRIPTOR
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
        let n = self.phi.len();
        self.forward_sweep();
        let (h, k) = (self.h, self.k);
        let courant = k * k / (h * h);
        let (phi, prev, next) = (&self.phi[..n], &self.prev[..n], &mut self.prev2[..n]);
        let (c, d, f) = (
            &self.sweep_c[..n],
            &self.sweep_d[..n],
            &mut self.tension[..n],
        );
        // Back-substitution from F_{N−1} = 0 down to F_0, fused with the interior update (8):
        // when F_{i−1} is known, F_i and F_{i+1} are too.
        f[n - 1] = 0.0;
        let mut f_right = 0.0; // F_{i+1}
        let mut f_mid = d[n - 2]; // F_i, i = N − 2 (c_{N−2} multiplies F_{N−1} = 0)
        f[n - 2] = f_mid;
        let mut check = 0.0;
        for i in (1..n - 1).rev() {
            let f_left = d[i - 1] - c[i - 1] * f_mid; // F_{i−1}
            f[i - 1] = f_left;
            let (left, mid, right) = (phi[i - 1], phi[i], phi[i + 1]);
            // eq. (8): φ_tt = 2 F_s φ_s + F φ_ss, centred differences.
            let accel =
                0.5 * (f_right - f_left) * (right - left) + f_mid * (right - 2.0 * mid + left);
            let value = 2.0 * mid - prev[i] + courant * accel;
            next[i] = value;
            check += value;
            f_right = f_mid;
            f_mid = f_left;
        }
        let support_tension = f[0];
        if !(check.is_finite() && support_tension.is_finite()) {
            return Err(self.diverged("the angle or the tension"));
        }
        if support_tension <= 0.0 {
            return Err(Diverged {
                step: self.steps + 1,
                time: (self.steps + 1) as f64 * k,
                reason: format!(
                    "the support tension F_0 = {support_tension:.3e} fell to zero or below (the string went slack at the support, and the support condition (11) divides by F_0)"
                ),
            });
        }
        // eq. (11) with the sign of eq. (9): φ_0 = φ_2 + 2 (h / F_0) cos φ_1, all at t + k.
        next[0] = next[2] + self.sign * 2.0 * h / support_tension * next[1].cos();
        // eq. (12), free end φ_ss = 0: φ_{N−1} = 2 φ_{N−2} − φ_{N−3}.
        next[n - 1] = 2.0 * next[n - 2] - next[n - 3];
        if !(next[0].is_finite() && next[n - 1].is_finite()) {
            return Err(self.diverged("the end angle"));
        }
        // Rotate: φ(t+k) becomes φ, φ(t) becomes prev, φ(t−k) becomes prev2.
        std::mem::swap(&mut self.phi, &mut self.prev2);
        std::mem::swap(&mut self.prev, &mut self.prev2);
        self.steps += 1;
        Ok(())
    }

    fn energy(&self) -> Energy {
        // Angles and rates at the half step t − k/2, so that both are centred (O(k²)).
        let inv_k = 1.0 / self.k;
        energy::energy_of(self.phi.len(), |i| {
            (
                0.5 * (self.phi[i] + self.prev[i]),
                (self.phi[i] - self.prev[i]) * inv_k,
            )
        })
    }

    fn support_tension(&self) -> f64 {
        // F_i sits at s = (i + 1) h. The support condition (5), F_1 − F_0 = −h sin φ_0, is
        // the tension's slope at the support: one step of it above F_0 reaches s = 0.
        let h = 1.0 / self.phi.len().max(1) as f64;
        self.tension[0] + h * self.phi.first().map_or(0.0, |p| p.sin())
    }

    fn angles(&self) -> &[f64] {
        &self.phi
    }

    fn observe(&mut self, out: &mut Observation) {
        self.solve_tension();
        let inv_k = 1.0 / self.k;
        out.angle.clone_from(&self.phi);
        out.tangent.clear();
        out.angular_velocity.clear();
        out.angular_velocity.extend(
            self.phi
                .iter()
                .zip(&self.prev)
                .map(|(a, b)| (a - b) * inv_k),
        );
        out.angular_acceleration.clear();
        out.angular_acceleration.extend(
            (0..self.phi.len())
                .map(|i| (self.phi[i] - 2.0 * self.prev[i] + self.prev2[i]) * inv_k * inv_k),
        );
        out.tension.clone_from(&self.tension);
    }

    fn box_clone(&self) -> Box<dyn Method> {
        Box::new(self.clone())
    }
}
