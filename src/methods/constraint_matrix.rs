//! The matrix A = G M⁻¹ Gᵀ of a chain of N uniform rods held together by their joints, the
//! one `rattle` solves with, at one configuration, factorised by block Thomas in O(N).
//!
//! G is the Jacobian of the joint gaps g_j = end(rod j−1) − start(rod j) (the "end of rod −1"
//! is the support). For joint j it has the blocks [I, (h/2) n_{j−1}] on rod j−1 (centre,
//! angle) and [−I, (h/2) n_j] on rod j, n the rod's unit normal. With M = diag(h, h, h³/12)
//! per rod, A is block-tridiagonal with 2×2 blocks, P = n nᵀ:
//!
//! * h A_00 = I + 3P_0;  h A_jj = 2I + 3P_{j−1} + 3P_j;  h A_{j,j+1} = h A_{j+1,j} = 3P_j − I,
//!
//! the same system as the chain's joint forces (`joint_forces.rs`). It is symmetric positive
//! definite, so every pivot block is invertible.

use nalgebra::{Matrix2, Vector2};

/// A 2×2 matrix's adjugate and the reciprocal of its determinant: its inverse is their
/// product, with one division where nalgebra's `try_inverse` makes four (docs/measurements.md).
/// Apart, an elimination can work with the adjugate while the division is under way. NaN
/// where the matrix is singular or not finite, which the callers' checks of finiteness show.
#[inline(always)]
fn adjugate(m: Matrix2<f64>) -> (Matrix2<f64>, f64) {
    let det = m.m11 * m.m22 - m.m12 * m.m21;
    let inv = if det == 0.0 { f64::NAN } else { 1.0 / det };
    (Matrix2::new(m.m22, -m.m12, -m.m21, m.m11), inv)
}

/// What one joint of a block elimination with the off-diagonal blocks U on both sides passes
/// to the next pivot, U D'⁻¹ U: kept as U adj(D') U and 1/det(D') apart, so that the next
/// pivot waits on the division alone, not on the products after it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Passed {
    product: Matrix2<f64>,
    inv_det: f64,
}

impl Passed {
    /// Before the first joint: nothing.
    pub(crate) fn none() -> Self {
        Self {
            product: Matrix2::zeros(),
            inv_det: 0.0,
        }
    }

    /// U D'⁻¹ U, which the next pivot block subtracts: D'_{j+1} = D_{j+1} − U D'⁻¹ U.
    #[inline(always)]
    pub(crate) fn schur(&self) -> Matrix2<f64> {
        self.inv_det * self.product
    }
}

/// One joint of the elimination: from its pivot block D' and its off-diagonal block U, the
/// inverted pivot D'⁻¹, the gain D'⁻¹ U for the back-substitution (zero at the `last` joint)
/// and what passes to the next pivot. A non-finite or singular pivot makes NaN, which the
/// callers' checks of finiteness show.
#[inline(always)]
pub(crate) fn eliminate(
    diag: Matrix2<f64>,
    upper: Matrix2<f64>,
    last: bool,
) -> (Matrix2<f64>, Matrix2<f64>, Passed) {
    let (adjugate, inv_det) = adjugate(diag);
    let passed = Passed {
        product: upper * adjugate * upper,
        inv_det,
    };
    let pivot = inv_det * adjugate;
    let gain = if last {
        Matrix2::zeros()
    } else {
        pivot * upper
    };
    (pivot, gain, passed)
}

/// h A at one configuration, factorised: D'_j = D_j − U_{j−1} D'_{j−1}⁻¹ U_{j−1}.
#[derive(Clone, Debug)]
pub(crate) struct ConstraintMatrix {
    /// Unit normals n_i of the rods at the configuration (G's rotational entries).
    pub(crate) normal: Vec<Vector2<f64>>,
    /// D'_j⁻¹, the inverted pivots.
    pivot: Vec<Matrix2<f64>>,
    /// U_j = 3P_j − I, the off-diagonal blocks.
    upper: Vec<Matrix2<f64>>,
    /// D'_j⁻¹ U_j, for the back-substitution (zero for the last joint).
    pub(crate) gain: Vec<Matrix2<f64>>,
}

impl ConstraintMatrix {
    pub(crate) fn new(n: usize) -> Self {
        Self {
            normal: vec![Vector2::zeros(); n],
            pivot: vec![Matrix2::zeros(); n],
            upper: vec![Matrix2::zeros(); n],
            gain: vec![Matrix2::zeros(); n],
        }
    }

    /// Factorises h A for rods along the unit tangents `tangent`.
    pub(crate) fn factorise(&mut self, tangent: &[Vector2<f64>]) {
        let eye = Matrix2::identity();
        let n = tangent.len();
        for (normal, t) in self.normal.iter_mut().zip(tangent) {
            *normal = Vector2::new(-t.y, t.x);
        }
        let projector = |v: &Vector2<f64>| 3.0 * v * v.transpose();
        let mut p_prev = projector(&self.normal[0]);
        let mut diag = eye + p_prev;
        // Over zipped slices, what the next pivot needs of this joint carried along: no bound
        // checked and no vector's pointer reloaded at each joint.
        let mut passed = Passed::none();
        let blocks = self
            .pivot
            .iter_mut()
            .zip(&mut self.upper)
            .zip(&mut self.gain);
        for (j, (((pivot, upper), gain), normal)) in blocks.zip(&self.normal).enumerate() {
            if j > 0 {
                let p = projector(normal);
                diag = 2.0 * eye + p_prev + p - passed.schur();
                p_prev = p;
            }
            *upper = p_prev - eye;
            // A non-finite configuration makes NaN here, which the caller detects.
            (*pivot, *gain, passed) = eliminate(diag, *upper, j + 1 == n);
        }
    }

    /// The forward half of solving A x = r: `x` holds r on entry and y_j = D'_j⁻¹ (h r_j −
    /// U_{j−1} y_{j−1}) on exit. Then x_j = y_j − gain_j x_{j+1}, from the last joint back,
    /// which the caller fuses with what it does with x.
    pub(crate) fn forward(&self, h: f64, x: &mut [Vector2<f64>]) {
        let mut before = Vector2::zeros();
        let mut upper_before = Matrix2::zeros();
        let blocks = self.pivot.iter().zip(&self.upper);
        for (j, (xj, (pivot, upper))) in x.iter_mut().zip(blocks).enumerate() {
            let r = if j > 0 {
                h * *xj - upper_before * before
            } else {
                h * *xj
            };
            before = pivot * r;
            *xj = before;
            upper_before = *upper;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The adjugate over the determinant is the inverse: its products with the matrix are
    /// the identity to round-off, as nalgebra's four-division one is; singular, it is NaN.
    #[test]
    fn inverse_by_one_division() {
        let m = Matrix2::new(2.0, -0.7, 0.3, 1.1);
        let (adjugate_of_m, inv_det) = adjugate(m);
        let inv = inv_det * adjugate_of_m;
        let reference = m.try_inverse().expect("invertible");
        assert!((inv * m - Matrix2::identity()).amax() < 1e-15);
        assert!((m * inv - Matrix2::identity()).amax() < 1e-15);
        assert!((inv - reference).amax() < 1e-15);
        let singular = Matrix2::new(1.0, 2.0, 2.0, 4.0);
        let (adjugate_of_singular, inv_det) = adjugate(singular);
        assert!((inv_det * adjugate_of_singular).iter().all(|x| x.is_nan()));
    }

    /// The factorisation solves h A x = h r: the forward pass and the back-substitution
    /// x_j = y_j − gain_j x_{j+1} give x, whose product with h A (assembled from its blocks
    /// as the module's note gives them) is h r to round-off.
    #[test]
    fn the_factorisation_solves_the_joints_system() {
        let angles = [0.3, -1.2, 2.0, 0.1, 0.7, -0.4];
        let tangent: Vec<Vector2<f64>> = angles
            .iter()
            .map(|&a: &f64| Vector2::new(a.cos(), a.sin()))
            .collect();
        let n = tangent.len();
        let h = 1.0 / n as f64;
        let mut matrix = ConstraintMatrix::new(n);
        matrix.factorise(&tangent);
        let r: Vec<Vector2<f64>> = (0..n)
            .map(|j| Vector2::new(j as f64 - 2.0, 1.0 + 0.5 * j as f64))
            .collect();
        let mut x = r.clone();
        matrix.forward(h, &mut x);
        for j in (0..n.saturating_sub(1)).rev() {
            let after = x[j + 1];
            x[j] -= matrix.gain[j] * after;
        }
        let eye = Matrix2::identity();
        let p: Vec<Matrix2<f64>> = matrix
            .normal
            .iter()
            .map(|v| 3.0 * v * v.transpose())
            .collect();
        for j in 0..n {
            let diag = if j == 0 {
                eye + p[0]
            } else {
                2.0 * eye + p[j - 1] + p[j]
            };
            let mut row = diag * x[j];
            if j > 0 {
                row += (p[j - 1] - eye) * x[j - 1];
            }
            if j + 1 < n {
                row += (p[j] - eye) * x[j + 1];
            }
            assert!(
                (row - h * r[j]).amax() < 1e-12,
                "joint {j}: {row} against {}",
                h * r[j]
            );
        }
    }
}
