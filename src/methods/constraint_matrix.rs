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

/// The inverse of a 2×2 matrix: its adjugate times one reciprocal of the determinant, where
/// nalgebra's `try_inverse` divides four times (docs/measurements.md); NaN where the matrix is
/// singular or not finite, which the callers' checks of finiteness then show.
#[inline(always)]
pub(crate) fn inverse(m: Matrix2<f64>) -> Matrix2<f64> {
    let det = m.m11 * m.m22 - m.m12 * m.m21;
    let inv = if det == 0.0 { f64::NAN } else { 1.0 / det };
    Matrix2::new(m.m22 * inv, -m.m12 * inv, -m.m21 * inv, m.m11 * inv)
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
        // Over zipped slices, the blocks of the joint before carried along: no bound checked
        // and no vector's pointer reloaded at each joint.
        let (mut upper_before, mut gain_before) = (Matrix2::zeros(), Matrix2::zeros());
        let blocks = self
            .pivot
            .iter_mut()
            .zip(&mut self.upper)
            .zip(&mut self.gain);
        for (j, (((pivot, upper), gain), normal)) in blocks.zip(&self.normal).enumerate() {
            if j > 0 {
                let p = projector(normal);
                diag = 2.0 * eye + p_prev + p - upper_before * gain_before;
                p_prev = p;
            }
            *upper = p_prev - eye;
            // A non-finite configuration makes NaN here, which the caller detects.
            *pivot = inverse(diag);
            *gain = if j + 1 < n {
                *pivot * *upper
            } else {
                Matrix2::zeros()
            };
            (upper_before, gain_before) = (*upper, *gain);
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

    /// The one-division inverse is the inverse: its products with the matrix are the
    /// identity to round-off, as nalgebra's four-division one is; singular, it is NaN.
    #[test]
    fn inverse_by_one_division() {
        let m = Matrix2::new(2.0, -0.7, 0.3, 1.1);
        let inv = inverse(m);
        let reference = m.try_inverse().expect("invertible");
        assert!((inv * m - Matrix2::identity()).amax() < 1e-15);
        assert!((m * inv - Matrix2::identity()).amax() < 1e-15);
        assert!((inv - reference).amax() < 1e-15);
        let singular = Matrix2::new(1.0, 2.0, 2.0, 4.0);
        assert!(inverse(singular).iter().all(|x| x.is_nan()));
    }
}
