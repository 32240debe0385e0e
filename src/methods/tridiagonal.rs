//! The bare tridiagonal (Thomas) solve: the floor every step of the seed scheme is measured
//! against, and a reference the scheme's fused solve is tested with.

/// Reusable scratch for [`solve`], so that repeated solves allocate nothing.
#[derive(Clone, Debug, Default)]
pub struct Workspace {
    upper: Vec<f64>,
    rhs: Vec<f64>,
}

impl Workspace {
    /// Scratch for systems of `n` unknowns.
    pub fn new(n: usize) -> Self {
        Self {
            upper: vec![0.0; n],
            rhs: vec![0.0; n],
        }
    }
}

/// Solves `lower[i] x[i-1] + diag[i] x[i] + upper[i] x[i+1] = rhs[i]` for `x` by Thomas'
/// algorithm in O(n), without pivoting (the systems here are diagonally dominant).
/// `lower[0]` and `upper[n-1]` are ignored. All slices must have the same length as `x`
/// and the workspace must have been made for at least that length.
pub fn solve(
    lower: &[f64],
    diag: &[f64],
    upper: &[f64],
    rhs: &[f64],
    x: &mut [f64],
    ws: &mut Workspace,
) {
    let n = x.len();
    if n == 0 {
        return;
    }
    let (c, d) = (&mut ws.upper[..n], &mut ws.rhs[..n]);
    let (diag, upper, lower, rhs) = (&diag[..n], &upper[..n], &lower[..n], &rhs[..n]);
    c[0] = upper[0] / diag[0];
    d[0] = rhs[0] / diag[0];
    for i in 1..n {
        let inv = 1.0 / (diag[i] - lower[i] * c[i - 1]);
        c[i] = upper[i] * inv;
        d[i] = (rhs[i] - lower[i] * d[i - 1]) * inv;
    }
    x[n - 1] = d[n - 1];
    for i in (0..n - 1).rev() {
        x[i] = d[i] - c[i] * x[i + 1];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_small_system_exactly() {
        // [2 1 0; 1 3 1; 0 1 2] x = [3, 5, 3]  ->  x = [1, 1, 1]
        let (l, d, u) = ([0.0, 1.0, 1.0], [2.0, 3.0, 2.0], [1.0, 1.0, 0.0]);
        let mut x = [0.0; 3];
        let mut ws = Workspace::new(3);
        solve(&l, &d, &u, &[3.0, 5.0, 3.0], &mut x, &mut ws);
        for xi in x {
            assert!((xi - 1.0).abs() < 1e-14);
        }
    }
}
