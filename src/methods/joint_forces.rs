//! The joint forces of a chain of N uniform rigid rods hinged at the support, and the angular
//! accelerations they cause: a symmetric positive-definite block-tridiagonal system with 2×2
//! blocks, solved by block Thomas in O(N) (the system is written out in `chain.rs`). Used to
//! step the `chain` method, and to observe the tension of any chain of rods.

use super::method::Observation;
use crate::model::geometry;
use nalgebra::Vector2;

/// Scratch of the joint-force solve, reused every evaluation.
#[derive(Clone, Debug)]
pub(crate) struct ForceSolver {
    /// G_j = D'_j⁻¹ U_j, row by row (xx, xy, yx, yy).
    gain: Vec<[f64; 4]>,
    /// g_j = D'_j⁻¹ r'_j
    offset: Vec<Vector2<f64>>,
    /// Joint forces f_0 … f_{N−1} (f_N = 0).
    pub(crate) force: Vec<Vector2<f64>>,
    /// Unit tangents (cos φ_i, sin φ_i) of the rods at the evaluation state; the normals are
    /// n_i = (−sin φ_i, cos φ_i).
    pub(crate) tangent: Vec<Vector2<f64>>,
    /// The tangents at the angles last given to [`ForceSolver::orient`]: what
    /// [`ForceSolver::orient_turned`] turns from.
    base: Vec<Vector2<f64>>,
    /// The angles the base tangents are at, and how many times [`ForceSolver::orient_moved`]
    /// has turned them since they were last worked out by a sine and cosine each.
    base_angle: Vec<f64>,
    moves: Option<u32>,
    /// Gravity per unit mass in the frame the rods are written in (y down): (0, 1) under a
    /// fixed support, (−ẍ_s(t), 1) in the frame of a shaken one ([`Support::gravity`]). Only
    /// the support's row of the system carries it: every rod falls alike, so at the other
    /// joints it cancels.
    ///
    /// [`Support::gravity`]: crate::model::support::Support::gravity
    pub(crate) gravity: Vector2<f64>,
}

/// How many times [`ForceSolver::orient_moved`] turns the tangents before it works them out
/// afresh.
const REANCHOR: u32 = 1024;

/// The symmetric 2×2 block 3 n nᵀ (xx, xy, yy) of a rod with unit tangent `t` (n its normal).
#[inline(always)]
fn projector(t: Vector2<f64>) -> [f64; 3] {
    [3.0 * t.y * t.y, -3.0 * t.x * t.y, 3.0 * t.x * t.x]
}

impl ForceSolver {
    pub(crate) fn new(n: usize) -> Self {
        Self {
            gain: vec![[0.0; 4]; n],
            offset: vec![Vector2::zeros(); n],
            force: vec![Vector2::zeros(); n],
            tangent: vec![Vector2::zeros(); n],
            // Sized at the first `orient`: a method that never orients by angles (its
            // tangents carried) never needs them.
            base: Vec::new(),
            base_angle: Vec::new(),
            moves: None,
            gravity: Vector2::new(0.0, 1.0),
        }
    }

    /// Orients the rods at angles `phi`, and keeps these tangents as the base that
    /// [`ForceSolver::orient_turned`] turns from.
    pub(crate) fn orient(&mut self, phi: &[f64]) {
        self.base.resize(phi.len(), Vector2::zeros());
        self.base_angle.resize(phi.len(), 0.0);
        for ((t, b), &angle) in self.tangent.iter_mut().zip(&mut self.base).zip(phi) {
            *t = geometry::tangent(angle);
            *b = *t;
        }
        self.base_angle.copy_from_slice(phi);
        self.moves = Some(0);
    }

    /// Orients the rods at angles `phi` as [`ForceSolver::orient`] does, by turning the base
    /// tangents through each rod's angle less the base's ([`geometry::turned`]: a short series
    /// where the turn is under 0.1 rad) rather than by a sine and cosine each: between the
    /// chain's steps its rods turn little. These tangents become the base. Every
    /// [`REANCHOR`]-th time, and the first, they are worked out afresh, so that the round-off
    /// of the turns (about 1e-16 each) cannot gather. At the base's own angles (a frame's
    /// observation, then the step after it) the base serves as it is and nothing is counted:
    /// what is observed never changes the run.
    pub(crate) fn orient_moved(&mut self, phi: &[f64]) {
        match self.moves {
            Some(_) if self.base_angle.as_slice() == phi => {
                self.tangent.copy_from_slice(&self.base);
            }
            Some(moves) if moves < REANCHOR => {
                let rods = self.tangent.iter_mut().zip(&mut self.base);
                for ((t, b), (a, &angle)) in rods.zip(self.base_angle.iter_mut().zip(phi)) {
                    *t = geometry::turned(*b, angle - *a);
                    *b = *t;
                    *a = angle;
                }
                self.moves = Some(moves + 1);
            }
            _ => self.orient(phi),
        }
    }

    /// The rods' unit tangents at angles `phi`, where the base is at these very angles (to
    /// round-off, their sines and cosines): what the tip and the energy are summed from
    /// without a sine and cosine a rod. `None` where the base is elsewhere.
    pub(crate) fn tangents_at(&self, phi: &[f64]) -> Option<&[Vector2<f64>]> {
        (self.moves.is_some() && self.base_angle.as_slice() == phi).then_some(self.base.as_slice())
    }

    /// Orients the rods at the base angles (the last [`ForceSolver::orient`]) plus `turn`:
    /// an RK4 stage's angles, φ + a φ̇, from the step's own by rotation rather than by a sine
    /// and cosine of each rod (the turns within a step are small: [`geometry::turned`]).
    pub(crate) fn orient_turned(&mut self, turn: &[f64]) {
        for ((t, b), &delta) in self.tangent.iter_mut().zip(&self.base).zip(turn) {
            *t = geometry::turned(*b, delta);
        }
    }

    /// Joint forces at the orientation set last ([`ForceSolver::orient`] or
    /// [`ForceSolver::orient_turned`]) and rates `omega`, then the angular accelerations, for
    /// rods of lengths `length` (summing to 1, mass equal to length; `None`: N equal rods).
    /// Returns the largest joint force and the largest |φ̇|, which set the stable step.
    ///
    /// Each joint's row of the system is the uniform one (module doc of `chain.rs`) with every
    /// rod's blocks divided by its own mass, multiplied through by the length of the rod after
    /// the joint; for equal rods the ratio of neighbours' lengths is 1 and the rows are the
    /// uniform ones. Block Thomas, every block written out: the pivots D'_j and U_j G_j are
    /// symmetric (U_j = 3P_j − I is), so three numbers each.
    pub(crate) fn solve(
        &mut self,
        omega: &[f64],
        length: Option<&[f64]>,
        alpha: &mut [f64],
    ) -> (f64, f64) {
        let max_rate = omega.iter().fold(0.0f64, |m, w| m.max(w.abs()));
        let max_force = match length {
            // Written twice so that equal rods' ratio of 1 folds away.
            None => {
                let h = 1.0 / omega.len() as f64;
                self.eliminate(omega, alpha, |_| h, |_| 1.0)
            }
            Some(l) => self.eliminate(omega, alpha, |i| l[i], |j| l[j] / l[j - 1]),
        };
        (max_force, max_rate)
    }

    /// Block Thomas for rods of lengths `rod(i)`, the ratio of rod j's length to rod j − 1's
    /// being `ratio(j)`; returns the largest joint force. The forward sweep is a chain of
    /// dependent 2×2 inversions, so what the next pivot needs (U_j G_j = U_j adj(D'_j) U_j /
    /// det D'_j) is formed beside the determinant and scaled once it is known, off the chain.
    #[inline(always)]
    fn eliminate(
        &mut self,
        omega: &[f64],
        alpha: &mut [f64],
        rod: impl Fn(usize) -> f64,
        ratio: impl Fn(usize) -> f64,
    ) -> f64 {
        let n = omega.len();
        // Forward elimination. What row j + 1 takes from row j: U_j G_j (symmetric) and U_j g_j.
        let mut carry = [0.0; 3];
        let mut carry_rhs = Vector2::zeros();
        let mut p_prev = [0.0; 3];
        // The centripetal pull of rod i on its ends, (h_i/2) φ̇_i² t_i.
        let mut spin_prev = Vector2::zeros();
        // Over zipped slices, as the back-substitution below: no bound checked and no
        // vector's pointer reloaded at each rod.
        let (tangent, offset, gain) = (
            &self.tangent[..n],
            &mut self.offset[..n],
            &mut self.gain[..n],
        );
        let rows = omega
            .iter()
            .zip(tangent)
            .zip(offset.iter_mut().zip(gain.iter_mut()));
        for (j, ((&rate, &t), (offset, gain))) in rows.enumerate() {
            let p = projector(t);
            let l = rod(j);
            let spin = 0.5 * l * rate * rate * t;
            let (d, rhs) = if j == 0 {
                // (I + 3P_0) f_0 + … = −m_0 ŷ − m_0 (h_0/2) φ̇_0² t_0
                ([1.0 + p[0], p[1], 1.0 + p[2]], l * (-self.gravity - spin))
            } else {
                let ratio = ratio(j);
                (
                    [
                        ratio * (1.0 + p_prev[0] - carry[0]) + 1.0 + p[0],
                        ratio * (p_prev[1] - carry[1]) + p[1],
                        ratio * (1.0 + p_prev[2] - carry[2]) + 1.0 + p[2],
                    ],
                    -l * (spin_prev + spin) - ratio * carry_rhs,
                )
            };
            // The system is SPD, so every pivot is invertible; a zero or non-finite
            // determinant means the state is already non-finite, which the caller detects.
            let inv_det = 1.0 / (d[0] * d[2] - d[1] * d[1]);
            // adj(D') r'
            let (ar_x, ar_y) = (d[2] * rhs.x - d[1] * rhs.y, d[0] * rhs.y - d[1] * rhs.x);
            let g = Vector2::new(ar_x * inv_det, ar_y * inv_det);
            *offset = g;
            if j + 1 < n {
                // U_j = 3P_j − I; adj(D'_j) U_j, then G_j = adj(D'_j) U_j / det.
                let (uxx, uxy, uyy) = (p[0] - 1.0, p[1], p[2] - 1.0);
                let au = [
                    d[2] * uxx - d[1] * uxy,
                    d[2] * uxy - d[1] * uyy,
                    d[0] * uxy - d[1] * uxx,
                    d[0] * uyy - d[1] * uxy,
                ];
                let uau = [
                    uxx * au[0] + uxy * au[2],
                    uxx * au[1] + uxy * au[3],
                    uxy * au[1] + uyy * au[3],
                ];
                *gain = au.map(|x| x * inv_det);
                carry = uau.map(|x| x * inv_det);
                carry_rhs = Vector2::new(uxx * g.x + uxy * g.y, uxy * g.x + uyy * g.y);
            } else {
                *gain = [0.0; 4];
            }
            p_prev = p;
            spin_prev = spin;
        }
        // Back-substitution, f_j = g_j − G_j f_{j+1}, and φ̈_i = −(6/(m_i h_i)) n_i · (f_i + f_{i+1}).
        let mut after = Vector2::zeros(); // f_{j+1}
        let mut max_force2: f64 = 0.0;
        let rows = self.gain[..n].iter().zip(&self.offset[..n]);
        let rods = (self.force[..n].iter_mut().zip(&self.tangent[..n])).zip(&mut alpha[..n]);
        for (j, ((gain, offset), ((force, t), alpha))) in rows.zip(rods).enumerate().rev() {
            let f = offset
                - Vector2::new(
                    gain[0] * after.x + gain[1] * after.y,
                    gain[2] * after.x + gain[3] * after.y,
                );
            *force = f;
            let (sum, l) = (f + after, rod(j));
            *alpha = -6.0 / (l * l) * (t.x * sum.y - t.y * sum.x);
            max_force2 = max_force2.max(f.norm_squared());
            after = f;
        }
        max_force2.sqrt()
    }

    /// The joint forces of rods whose unit tangents are `tangent`, turning at `rate`, into
    /// `force`, and their angular accelerations into `alpha`: the solve an observation makes,
    /// for a method that carries its tangents.
    pub(crate) fn solve_at(&mut self, tangent: &[Vector2<f64>], rate: &[f64], alpha: &mut [f64]) {
        self.tangent.copy_from_slice(tangent);
        // The base no longer stands for these tangents.
        self.moves = None;
        self.solve(rate, None, alpha);
    }

    /// Fills an observation of rods at `angle` turning at `rate`, whose unit tangents a
    /// method carries as `tangent` (its angles' sines and cosines to round-off): the angles,
    /// rates, angular accelerations and tensions the joint forces give there. The solve and
    /// the frame take the tangents as they are, without a sine and cosine a rod, so that the
    /// frame's nodes are the method's own.
    pub(crate) fn observe(
        &mut self,
        angle: &[f64],
        tangent: &[Vector2<f64>],
        rate: &[f64],
        out: &mut Observation,
    ) {
        out.angular_acceleration.resize(rate.len(), 0.0);
        self.solve_at(tangent, rate, &mut out.angular_acceleration);
        out.angle.clear();
        out.angle.extend_from_slice(angle);
        out.angular_velocity.clear();
        out.angular_velocity.extend_from_slice(rate);
        out.tangent.clear();
        out.tangent.extend_from_slice(tangent);
        self.tension(&mut out.tension);
    }

    /// Tension on each rod: the mean pull of its two joints along it.
    pub(crate) fn tension(&self, out: &mut Vec<f64>) {
        out.resize(self.force.len(), 0.0);
        let mut after = Vector2::zeros(); // the free end's joint pulls with nothing
        let rods = out.iter_mut().zip(&self.tangent).zip(&self.force);
        for ((tension, t), force) in rods.rev() {
            *tension = rod_tension(t, force, &after);
            after = *force;
        }
    }

    /// The tension on rod `i` alone (see [`ForceSolver::tension`]); 0 past the last.
    pub(crate) fn tension_of(&self, i: usize) -> f64 {
        let (Some(t), Some(force)) = (self.tangent.get(i), self.force.get(i)) else {
            return 0.0;
        };
        let after = self
            .force
            .get(i + 1)
            .copied()
            .unwrap_or_else(Vector2::zeros);
        rod_tension(t, force, &after)
    }
}

/// The tension of a rod with unit tangent `t` between its joints' forces `force` (at its
/// upper end) and `after` (at its lower): the mean pull of the two along it.
#[inline(always)]
fn rod_tension(t: &Vector2<f64>, force: &Vector2<f64>, after: &Vector2<f64>) -> f64 {
    -0.5 * t.dot(&(force + after))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::energy;
    use nalgebra::{DMatrix, DVector};

    /// Rods oriented by turning (`orient_moved`) lie where a sine and cosine each put them,
    /// to round-off, however many moves; at the base's own angles a second orientation (a
    /// frame's, then the step's) changes nothing, the count of moves included, so that
    /// observing never changes the run.
    #[test]
    fn orienting_by_turns_is_orienting() {
        let n = 50;
        let mut solver = ForceSolver::new(n);
        let angles = |t: f64| -> Vec<f64> {
            (0..n)
                .map(|i| 0.5 + (1.0 + i as f64 * 0.1) * t.sin())
                .collect()
        };
        let mut worst: f64 = 0.0;
        for step in 0..3 * REANCHOR {
            let phi = angles(step as f64 * 1e-3);
            solver.orient_moved(&phi);
            for (t, &angle) in solver.tangent.iter().zip(&phi) {
                worst = worst.max((t - geometry::tangent(angle)).amax());
            }
        }
        assert!(worst < 1e-13, "turned tangents strayed by {worst:e}");
        let phi = angles(0.123);
        solver.orient_moved(&phi);
        let (tangents, moves) = (solver.tangent.clone(), solver.moves);
        solver.orient_turned(&vec![0.01; n]); // an RK4 stage moves the tangents, not the base
        solver.orient_moved(&phi);
        assert_eq!(solver.tangent, tangents);
        assert_eq!(solver.moves, moves);
        // The tip and the energy from the base: as from the sines and cosines, to round-off;
        // at other angles, no tangents.
        let tangents = solver.tangents_at(&phi).expect("oriented at phi");
        let tip = geometry::tip_of_tangents(tangents, None);
        assert!((tip - geometry::tip_of(&phi, None)).norm() < 1e-14);
        let rates: Vec<f64> = (0..n).map(|i| 0.3 - 0.07 * i as f64).collect();
        let (turned, exact) = (
            energy::energy_of_tangents(tangents, &rates, None),
            energy::energy(&phi, &rates),
        );
        assert!((turned.total() - exact.total()).abs() < 1e-14);
        assert!((turned.kinetic() - exact.kinetic()).abs() < 1e-14);
        assert!(solver.tangents_at(&angles(0.124)).is_none());
    }

    /// The joint forces from Newton–Euler for each rod and the condition that the support
    /// stays put and neighbouring rods' ends move together, written as one dense system and
    /// solved by LU: rod i's centre accelerates by (f_i − f_{i+1})/m_i + g, it turns by
    /// φ̈_i = −(6/(m_i h_i)) n_i · (f_i + f_{i+1}), and its ends by that ∓ (h_i/2)(φ̈_i n_i − φ̇_i² t_i).
    fn dense_forces(
        phi: &[f64],
        omega: &[f64],
        length: &[f64],
        gravity: Vector2<f64>,
    ) -> Vec<Vector2<f64>> {
        let n = phi.len();
        let t: Vec<_> = phi.iter().map(|&a| geometry::tangent(a)).collect();
        let normal = |i: usize| Vector2::new(-t[i].y, t[i].x);
        // An end's acceleration as (coefficients of f, constant): sign −1 its start, +1 its end.
        let end = |i: usize, sign: f64| {
            let mut row = DMatrix::<f64>::zeros(2, 2 * n);
            let m = length[i];
            let turn = -6.0 / (m * length[i]);
            for (k, weight) in [(i, 1.0), (i + 1, -1.0)] {
                if k == n {
                    continue;
                }
                for c in 0..2 {
                    let mut unit = Vector2::zeros();
                    unit[c] = 1.0;
                    // Centre: weight f_k / m; turning: n · (f_i + f_{i+1}), both ends add.
                    let centre = weight * unit / m;
                    let spin = sign * 0.5 * length[i] * turn * normal(i).dot(&unit) * normal(i);
                    let column = centre + spin;
                    row[(0, 2 * k + c)] += column.x;
                    row[(1, 2 * k + c)] += column.y;
                }
            }
            let constant = gravity - sign * 0.5 * length[i] * omega[i] * omega[i] * t[i];
            (row, constant)
        };
        let mut a = DMatrix::<f64>::zeros(2 * n, 2 * n);
        let mut b = DVector::<f64>::zeros(2 * n);
        for j in 0..n {
            // Joint j: the start of rod j where the end of rod j − 1 (or the support) is.
            let (start, c_start) = end(j, -1.0);
            let (row, constant) = match j {
                0 => (start, c_start),
                _ => {
                    let (before, c_before) = end(j - 1, 1.0);
                    (start - before, c_start - c_before)
                }
            };
            a.view_mut((2 * j, 0), (2, 2 * n)).copy_from(&row);
            b[2 * j] = -constant.x;
            b[2 * j + 1] = -constant.y;
        }
        let f = a.lu().solve(&b).expect("the system is regular");
        (0..n)
            .map(|j| Vector2::new(f[2 * j], f[2 * j + 1]))
            .collect()
    }

    #[test]
    fn the_joint_forces_keep_the_rods_joined_equal_and_graded() {
        for n in [2, 3, 9, 10] {
            joined(n);
        }
    }

    fn joined(n: usize) {
        // A bent, spinning chain, and a shaken support's sideways gravity.
        let phi: Vec<f64> = (0..n)
            .map(|i| 0.3 + 0.9 * (i as f64).sin() - 0.2 * i as f64)
            .collect();
        let omega: Vec<f64> = (0..n).map(|i| 2.0 * (1.7 * i as f64).cos()).collect();
        let gravity = Vector2::new(-0.4, 1.0);
        let equal = vec![1.0 / n as f64; n];
        let edge = |i: usize| 1.0 - (1.0 - i as f64 / n as f64).powf(1.5);
        let graded: Vec<f64> = (0..n).map(|i| edge(i + 1) - edge(i)).collect();
        for (length, rods) in [(None, &equal), (Some(graded.as_slice()), &graded)] {
            let mut solver = ForceSolver::new(n);
            solver.gravity = gravity;
            let mut alpha = vec![0.0; n];
            solver.orient(&phi);
            solver.solve(&omega, length, &mut alpha);
            let want = dense_forces(&phi, &omega, rods, gravity);
            for (j, (got, want)) in solver.force.iter().zip(&want).enumerate() {
                assert!(
                    (got - want).norm() < 1e-12 * (1.0 + want.norm()),
                    "N = {n}, graded: {}, joint {j}: {got:?} against {want:?}",
                    length.is_some()
                );
            }
            // And turned from another base: the same forces at the same angles.
            solver.orient(&vec![0.1; n]);
            let turn: Vec<f64> = phi.iter().map(|a| a - 0.1).collect();
            solver.orient_turned(&turn);
            let mut turned_alpha = vec![0.0; n];
            solver.solve(&omega, length, &mut turned_alpha);
            for (a, b) in alpha.iter().zip(&turned_alpha) {
                assert!((a - b).abs() < 1e-10 * (1.0 + a.abs()), "{a} against {b}");
            }
        }
    }
}
