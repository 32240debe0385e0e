//! The joint forces of a chain of N uniform rigid rods hinged at the support, and the angular
//! accelerations they cause: a symmetric positive-definite block-tridiagonal system with 2×2
//! blocks, solved by block Thomas in O(N) (the system is written out in `chain.rs`). Used to
//! step the `chain` method, and to observe the tension of any chain of rods.

use super::method::Observation;
use nalgebra::{Matrix2, Vector2};

/// Scratch of the joint-force solve, reused every evaluation.
#[derive(Clone, Debug)]
pub(crate) struct ForceSolver {
    /// G_j = D'_j⁻¹ U_j
    gain: Vec<Matrix2<f64>>,
    /// g_j = D'_j⁻¹ r'_j
    offset: Vec<Vector2<f64>>,
    /// Joint forces f_0 … f_{N−1} (f_N = 0).
    pub(crate) force: Vec<Vector2<f64>>,
    /// Unit tangents and normals of the rods at the evaluation state.
    pub(crate) tangent: Vec<Vector2<f64>>,
    normal: Vec<Vector2<f64>>,
    /// Gravity per unit mass in the frame the rods are written in (y down): (0, 1) under a
    /// fixed support, (−ẍ_s(t), 1) in the frame of a shaken one ([`Support::gravity`]). Only
    /// the support's row of the system carries it: every rod falls alike, so at the other
    /// joints it cancels.
    ///
    /// [`Support::gravity`]: crate::model::support::Support::gravity
    pub(crate) gravity: Vector2<f64>,
}

impl ForceSolver {
    pub(crate) fn new(n: usize) -> Self {
        Self {
            gain: vec![Matrix2::zeros(); n],
            offset: vec![Vector2::zeros(); n],
            force: vec![Vector2::zeros(); n],
            tangent: vec![Vector2::zeros(); n],
            normal: vec![Vector2::zeros(); n],
            gravity: Vector2::new(0.0, 1.0),
        }
    }

    /// The rods' tangents and normals at angles `phi`; returns the largest |φ̇| of `omega`.
    fn orient(&mut self, phi: &[f64], omega: &[f64]) -> f64 {
        let mut max_rate: f64 = 0.0;
        for i in 0..phi.len() {
            let (s, c) = phi[i].sin_cos();
            self.tangent[i] = Vector2::new(c, s);
            self.normal[i] = Vector2::new(-s, c);
            max_rate = max_rate.max(omega[i].abs());
        }
        max_rate
    }

    /// Joint forces for angles `phi` and rates `omega`, then the angular accelerations.
    /// Returns the largest joint force and the largest |φ̇|, which set the stable step.
    pub(crate) fn accelerations(
        &mut self,
        phi: &[f64],
        omega: &[f64],
        alpha: &mut [f64],
    ) -> (f64, f64) {
        let n = phi.len();
        let h = 1.0 / n as f64;
        let m = h;
        let eye = Matrix2::identity();
        let max_rate = self.orient(phi, omega);
        let projector = |v: &Vector2<f64>| 3.0 * v * v.transpose();
        let half_mh = 0.5 * m * h;
        // Forward elimination.
        let mut p_prev = projector(&self.normal[0]);
        let mut diag = eye + p_prev;
        let mut rhs = -m * self.gravity - half_mh * omega[0] * omega[0] * self.tangent[0];
        for j in 0..n {
            if j > 0 {
                let p = projector(&self.normal[j]);
                let lower = p_prev - eye; // 3P_{j−1} − I, also U_{j−1}
                diag = 2.0 * eye + p_prev + p - lower * self.gain[j - 1];
                rhs = -half_mh
                    * (omega[j - 1] * omega[j - 1] * self.tangent[j - 1]
                        + omega[j] * omega[j] * self.tangent[j])
                    - lower * self.offset[j - 1];
                p_prev = p;
            }
            // The system is SPD, so every pivot block is invertible; a failure means the
            // state is already non-finite, which the caller detects.
            let inv = diag
                .try_inverse()
                .unwrap_or_else(|| Matrix2::from_element(f64::NAN));
            self.gain[j] = if j + 1 < n {
                inv * (p_prev - eye) // U_j = 3P_j − I
            } else {
                Matrix2::zeros()
            };
            self.offset[j] = inv * rhs;
        }
        // Back-substitution and φ̈_i = −(6/(m h)) n_i · (f_i + f_{i+1}).
        let scale = -6.0 / (m * h);
        let mut after = Vector2::zeros(); // f_{j+1}
        let mut max_force2: f64 = 0.0;
        for j in (0..n).rev() {
            let f = self.offset[j] - self.gain[j] * after;
            self.force[j] = f;
            alpha[j] = scale * self.normal[j].dot(&(f + after));
            max_force2 = max_force2.max(f.norm_squared());
            after = f;
        }
        (max_force2.sqrt(), max_rate)
    }

    /// As [`ForceSolver::accelerations`], for rods of lengths `length` (summing to 1, mass
    /// equal to length): each joint's row of the system is the uniform one with every rod's
    /// blocks divided by its own mass, multiplied through by the length of the rod after the
    /// joint. For graded rods, shorter towards the free end.
    pub(crate) fn accelerations_graded(
        &mut self,
        phi: &[f64],
        omega: &[f64],
        length: &[f64],
        alpha: &mut [f64],
    ) -> (f64, f64) {
        let n = phi.len();
        let eye = Matrix2::identity();
        let max_rate = self.orient(phi, omega);
        let projector = |v: &Vector2<f64>| 3.0 * v * v.transpose();
        // The centripetal pull of rod i on its ends, (h_i/2) φ̇_i² t_i.
        let spin = |i: usize| 0.5 * length[i] * omega[i] * omega[i] * self.tangent[i];
        let mut p_prev = projector(&self.normal[0]);
        let mut diag = eye + p_prev;
        let mut rhs = length[0] * (-self.gravity - spin(0));
        for j in 0..n {
            if j > 0 {
                let p = projector(&self.normal[j]);
                let ratio = length[j] / length[j - 1];
                let lower = ratio * (p_prev - eye);
                diag = ratio * (eye + p_prev) + eye + p - lower * self.gain[j - 1];
                rhs = -length[j] * (spin(j - 1) + spin(j)) - lower * self.offset[j - 1];
                p_prev = p;
            }
            let inv = diag
                .try_inverse()
                .unwrap_or_else(|| Matrix2::from_element(f64::NAN));
            self.gain[j] = if j + 1 < n {
                inv * (p_prev - eye)
            } else {
                Matrix2::zeros()
            };
            self.offset[j] = inv * rhs;
        }
        let mut after = Vector2::zeros();
        let mut max_force2: f64 = 0.0;
        for j in (0..n).rev() {
            let f = self.offset[j] - self.gain[j] * after;
            self.force[j] = f;
            alpha[j] = -6.0 / (length[j] * length[j]) * self.normal[j].dot(&(f + after));
            max_force2 = max_force2.max(f.norm_squared());
            after = f;
        }
        (max_force2.sqrt(), max_rate)
    }

    /// Tension on each rod: the mean pull of its two joints along it.
    /// Fills an observation of rods at `angle` turning at `rate`: the angles, rates, angular
    /// accelerations and tensions the joint forces give there.
    pub(crate) fn observe(&mut self, angle: &[f64], rate: &[f64], out: &mut Observation) {
        out.angle.clear();
        out.angle.extend_from_slice(angle);
        out.angular_velocity.clear();
        out.angular_velocity.extend_from_slice(rate);
        out.angular_acceleration.resize(rate.len(), 0.0);
        self.accelerations(angle, rate, &mut out.angular_acceleration);
        self.tension(&mut out.tension);
    }

    pub(crate) fn tension(&self, out: &mut Vec<f64>) {
        let n = self.force.len();
        out.clear();
        out.extend((0..n).map(|i| {
            let after = if i + 1 < n {
                self.force[i + 1]
            } else {
                Vector2::zeros()
            };
            -0.5 * self.tangent[i].dot(&(self.force[i] + after))
        }));
    }
}
