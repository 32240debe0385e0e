//! How accurate a method is at N segments: tip error ≈ C h^p ([`ErrorModel`]), each method's
//! one committed law ([`law`]), and the least-squares fit of that law to measured errors (used
//! by `rope study` to fit it, by the pilots to fit the scene's own, and by the convergence
//! tests to measure an order).

use crate::methods::MethodKind;

/// What the pilots' model is multiplied by, beyond the scatter of its own fit: the margin
/// for an error that grows faster between the pilots' N and the chosen one than between the
/// pilots. (The live estimate's misses of the whip, by a factor near 3, come from dividing by
/// the method's nominal order; the pilots divide by the order they observe.) The mode theory's
/// model carries it too ([`crate::plan::committed::from_theory`]).
pub const SAFETY: f64 = 1.5;

/// Fewest segments the rule chooses: fewer is a pendulum, not a rope.
pub const MIN_SEGMENTS: usize = 4;

/// `method`'s one committed error law: the largest tip error up to t = 3 ≈ C h^p with its
/// measured safety factor, fitted by `rope study --estimate-check` over the releases at 0°,
/// 30°, 60°, 90° and modes 1 and 2 (`assets/estimate-check/`). `--tolerance` rests on it
/// where no atlas serves and the pilots measure nothing better.
pub fn law(method: MethodKind) -> ErrorModel {
    let (constant, order, safety) = match method {
        MethodKind::Seed => (1.985, 0.81, 1.03),
        MethodKind::Chain => (0.458, 1.00, 1.07),
        // The chain's one law, not refitted: it bounds every entry of the graded rods' atlas
        // (20° to 90°, N = 16 to 1131, at most 0.40/N; `plan::atlas`'s tests check it) and
        // their worst error from 30° at N = 50 within 3 times (`tests/estimate.rs`). Near the
        // horizontal, where the end rods spin on, the rule does not choose them.
        MethodKind::Graded => return law(MethodKind::Chain),
        MethodKind::Rattle => (0.459, 1.00, 1.07),
        MethodKind::Midpoint => (0.461, 1.00, 1.08),
    };
    ErrorModel {
        constant,
        order,
        safety,
    }
}

/// Tip error ≈ `constant` · h^`order`, and at most `safety` times that on the errors it was
/// fitted to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ErrorModel {
    pub constant: f64,
    pub order: f64,
    /// The largest measured error over the fit's prediction (≥ 1): what the prediction is
    /// multiplied by to bound every error it was fitted to.
    pub safety: f64,
}

impl ErrorModel {
    /// Predicted tip error at `segments`.
    pub fn predict(&self, segments: usize) -> f64 {
        self.constant * (1.0 / segments as f64).powf(self.order)
    }

    /// The predicted error with its safety factor: a bound on the errors it was fitted to.
    pub fn bound(&self, segments: usize) -> f64 {
        self.safety * self.predict(segments)
    }

    /// Fewest segments whose bound is at most `tolerance` (a count within 1e-9 of a whole
    /// one is that one: rounding does not add a segment).
    pub fn segments_for(&self, tolerance: f64) -> usize {
        let h = (tolerance / (self.safety * self.constant)).powf(1.0 / self.order);
        (1.0 / h - 1e-9).ceil() as usize
    }

    /// The least-squares fit of log(error) = log C + `order` · log h to `(segments, error)`
    /// points at the order given (errors ≤ 0 are left out): C the geometric mean of
    /// error / h^order, the safety its largest ratio to that. `None` without a point.
    pub fn fit_at_order(
        points: impl IntoIterator<Item = (usize, f64)>,
        order: f64,
    ) -> Option<ErrorModel> {
        let logs: Vec<f64> = points
            .into_iter()
            .filter(|&(_, e)| e > 0.0)
            .map(|(n, e)| e.ln() - order * (1.0 / n as f64).ln())
            .collect();
        if logs.is_empty() {
            return None;
        }
        let log_constant = logs.iter().sum::<f64>() / logs.len() as f64;
        let safety = logs
            .iter()
            .map(|l| (l - log_constant).exp())
            .fold(1.0, f64::max);
        Some(ErrorModel {
            constant: log_constant.exp(),
            order,
            safety,
        })
    }

    /// The least-squares fit of log(error) = log C + p log h to `(segments, error)` points
    /// (errors ≤ 0 are left out). `None` with fewer than two distinct segment counts.
    pub fn fit(points: impl IntoIterator<Item = (usize, f64)>) -> Option<ErrorModel> {
        let logs: Vec<(f64, f64)> = points
            .into_iter()
            .filter(|&(_, e)| e > 0.0)
            .map(|(n, e)| ((1.0 / n as f64).ln(), e.ln()))
            .collect();
        let m = logs.len() as f64;
        let (mx, my) = logs
            .iter()
            .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / m, b + y / m));
        let sxy: f64 = logs.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
        let sxx: f64 = logs.iter().map(|(x, _)| (x - mx) * (x - mx)).sum();
        if logs.len() < 2 || sxx <= 0.0 {
            return None;
        }
        let order = sxy / sxx;
        let constant = (my - order * mx).exp();
        // The largest residual above the line, as a factor.
        let safety = logs
            .iter()
            .map(|(x, y)| (y - (constant.ln() + order * x)).exp())
            .fold(1.0, f64::max);
        Some(ErrorModel {
            constant,
            order,
            safety,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_fit_at_a_given_order_bounds_every_point_it_was_fitted_to() {
        // Errors whose constant grows with N (a whip at coarse N), fitted at first order.
        let points = [(16, 2.8e-2), (32, 1.6e-2), (64, 9.0e-3)];
        let model = ErrorModel::fit_at_order(points, 1.0).unwrap();
        assert_eq!(model.order, 1.0);
        for (n, e) in points {
            assert!(model.bound(n) >= e * (1.0 - 1e-12), "N = {n}: {model:?}");
        }
        // The finest point is the one above the line: it sets the safety.
        assert!((model.bound(64) - 9.0e-3).abs() < 1e-12);
    }

    #[test]
    fn fit_recovers_an_exact_power_law() {
        let law = ErrorModel {
            constant: 0.3,
            order: 2.0,
            safety: 1.0,
        };
        let fitted = ErrorModel::fit([10, 20, 40].map(|n| (n, law.predict(n)))).unwrap();
        assert!((fitted.order - 2.0).abs() < 1e-12);
        assert!((fitted.constant - 0.3).abs() < 1e-12);
        assert!((fitted.safety - 1.0).abs() < 1e-9);
        assert_eq!(law.segments_for(law.predict(40)), 40);
    }

    #[test]
    fn the_safety_factor_is_the_largest_error_over_the_fit() {
        // Errors 1, 4, 1 × the law at three N: the fit lies below the middle point.
        let law = |n: usize| 0.1 / n as f64;
        let fitted = ErrorModel::fit([(10, law(10)), (20, 4.0 * law(20)), (40, law(40))]).unwrap();
        let worst = [(10, law(10)), (20, 4.0 * law(20)), (40, law(40))]
            .iter()
            .map(|&(n, e)| e / fitted.predict(n))
            .fold(0.0, f64::max);
        assert!((fitted.safety - worst).abs() < 1e-9 && fitted.safety > 1.0);
        assert!(fitted.bound(20) >= 4.0 * law(20) * (1.0 - 1e-12));
    }

    #[test]
    fn fit_needs_two_segment_counts() {
        assert!(ErrorModel::fit([(10, 1e-3)]).is_none());
        assert!(ErrorModel::fit([(10, 1e-3), (10, 2e-3)]).is_none());
    }
}
