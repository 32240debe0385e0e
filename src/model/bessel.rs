//! The small-oscillation modes of a hanging string (D. Bernoulli): the n-th mode's sideways
//! displacement is `J0(2 ω_n sqrt(1 − s))` with `ω_n = j_{0,n} / 2`, j_{0,n} the n-th zero of
//! the Bessel function J0. J0 and J1 come from `libm` (valid for every argument).

/// Bessel function of the first kind, order 0.
pub fn j0(x: f64) -> f64 {
    libm::j0(x)
}

/// Bessel function of the first kind, order 1 (J0' = −J1).
pub fn j1(x: f64) -> f64 {
    libm::j1(x)
}

/// The n-th positive zero of J0 (n ≥ 1), by Newton's method from McMahon's estimate.
pub fn j0_zero(n: u32) -> f64 {
    let mut x = (f64::from(n) - 0.25) * std::f64::consts::PI;
    for _ in 0..50 {
        let dx = j0(x) / -j1(x);
        x -= dx;
        if dx.abs() < 1e-15 * x {
            break;
        }
    }
    x
}

/// Angular frequency of the n-th small-oscillation mode of the hanging unit string
/// (g = L = 1): ω_n = j_{0,n} / 2.
pub fn mode_frequency(n: u32) -> f64 {
    j0_zero(n) / 2.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zeros_match_tabulated_values() {
        // Abramowitz & Stegun, table 9.5.
        assert!((j0_zero(1) - 2.404_825_557_695_773).abs() < 1e-12);
        assert!((j0_zero(2) - 5.520_078_110_286_311).abs() < 1e-12);
        assert!((j0_zero(3) - 8.653_727_912_911_013).abs() < 1e-11);
    }

    #[test]
    fn j1_matches_a_tabulated_value() {
        assert!((j1(1.0) - 0.440_050_585_744_933_5).abs() < 1e-14);
    }
}
