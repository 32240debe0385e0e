//! The folded chain let go at one end (Calkin & March, Am. J. Phys. 57, 154 (1989)): what an
//! energy-conserving string predicts for its free end. Units g = L = m = 1; `x` is how far the
//! free end has fallen, from 0 (let go, both ends at the support's height) to 1 (the chain
//! hangs straight).
//!
//! The held arm is at rest, (1 + x)/2 long; the falling arm, (1 − x)/2 long, moves down at the
//! free end's speed v. The potential energy is −(1 + 2x − x²)/4 and the kinetic energy
//! (1 − x) v²/4, so energy kept from rest gives v² = x (2 − x)/(1 − x): faster than free
//! fall's 2x from the first instant, and without bound as x → 1 (the final snap). The
//! support carries the weight less the rate of change of the falling arm's momentum,
//! F₀ = 1 − d/dt((1 − x) v/2) = (1 + x)/2 + v²/4.

/// The free end's speed once it has fallen `x` (0 ≤ x < 1): v = sqrt(x (2 − x)/(1 − x)).
pub fn speed(x: f64) -> f64 {
    (x * (2.0 - x) / (1.0 - x)).sqrt()
}

/// Free fall's speed after falling `x`, sqrt(2x): what the folded chain outruns.
pub fn free_fall_speed(x: f64) -> f64 {
    (2.0 * x).sqrt()
}

/// The free end's acceleration once it has fallen `x`: a = 1 + x (2 − x)/(2 (1 − x)²), more
/// than g from the start.
pub fn acceleration(x: f64) -> f64 {
    1.0 + x * (2.0 - x) / (2.0 * (1.0 - x).powi(2))
}

/// The tension at the support, in units of the chain's weight, once the free end has fallen
/// `x`: F₀ = (1 + x)/2 + v²/4.
pub fn support_tension(x: f64) -> f64 {
    (1.0 + x) / 2.0 + x * (2.0 - x) / (4.0 * (1.0 - x))
}

/// The string's downward momentum once the free end has fallen `x`: the falling arm's,
/// (1 − x) v/2 (the held arm is at rest).
pub fn momentum(x: f64) -> f64 {
    (1.0 - x) * speed(x) / 2.0
}

/// The time the free end takes to fall `x` (0 ≤ x ≤ 1): t = ∫ dx/v. With x = sin²θ the
/// integrand becomes smooth, t = ∫₀^asin√x 2 cos²θ / sqrt(1 + cos²θ) dθ, and Simpson's rule
/// on 256 intervals gives it to 1e-10.
pub fn time_to_fall(x: f64) -> f64 {
    let end = x.clamp(0.0, 1.0).sqrt().asin();
    let f = |theta: f64| {
        let c2 = theta.cos().powi(2);
        2.0 * c2 / (1.0 + c2).sqrt()
    };
    const INTERVALS: usize = 256;
    let h = end / INTERVALS as f64;
    let inner: f64 = (1..INTERVALS)
        .map(|i| f(i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 })
        .sum();
    h / 3.0 * (f(0.0) + inner + f(end))
}

/// How far the free end has fallen when its arm runs out, 1 − πd/2 for ends `gap` = d apart:
/// the half circle at the bottom, πd/2 of chain, is all that is left of the falling arm.
pub fn arm_runs_out(gap: f64) -> f64 {
    1.0 - std::f64::consts::PI * gap / 2.0
}

/// The snap: when the free arm runs out ([`arm_runs_out`]) and the bend whips round, at
/// [`time_to_fall`] of it (1.1944 for d = 0.02). Up to it the fall is smooth; from it on the
/// end's speed is [`speed`] there (5.6 string lengths a unit for d = 0.02) and its path is set by the bend's last rods.
pub fn snap_time(gap: f64) -> f64 {
    time_to_fall(arm_runs_out(gap))
}

/// How far the free end has fallen at time `t` (the inverse of [`time_to_fall`], by
/// bisection): 1 from the time the chain hangs straight on.
pub fn fall_at(t: f64) -> f64 {
    if t <= 0.0 {
        return 0.0;
    }
    if t >= time_to_fall(1.0) {
        return 1.0;
    }
    let (mut low, mut high) = (0.0, 1.0);
    for _ in 0..50 {
        let mid = 0.5 * (low + high);
        if time_to_fall(mid) < t {
            low = mid;
        } else {
            high = mid;
        }
    }
    0.5 * (low + high)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_free_end_starts_as_free_fall_and_outruns_it() {
        // Near x = 0, v² = 2x + O(x²) and a = 1 + x + O(x²).
        let x = 1e-6;
        assert!((speed(x) / free_fall_speed(x) - 1.0).abs() < 1e-6);
        assert!((acceleration(x) - 1.0).abs() < 2e-6);
        for x in [0.1, 0.5, 0.9] {
            assert!(speed(x) > free_fall_speed(x));
        }
    }

    #[test]
    fn the_acceleration_is_the_derivative_of_half_the_squared_speed() {
        for x in [0.1, 0.3, 0.6, 0.8] {
            let dx = 1e-6;
            let numeric = (speed(x + dx).powi(2) - speed(x - dx).powi(2)) / (4.0 * dx);
            assert!(
                (numeric - acceleration(x)).abs() < 1e-6 * acceleration(x),
                "x = {x}"
            );
        }
    }

    #[test]
    fn the_fall_time_is_the_integral_of_one_over_the_speed() {
        // Early on the fall is free: t = sqrt(2x) to first order.
        let x = 1e-6;
        assert!((time_to_fall(x) / (2.0 * x).sqrt() - 1.0).abs() < 1e-5);
        // dt/dx = 1/v, checked by differences.
        for x in [0.2, 0.5, 0.8] {
            let dx = 1e-5;
            let numeric = (time_to_fall(x + dx) - time_to_fall(x - dx)) / (2.0 * dx);
            assert!((numeric * speed(x) - 1.0).abs() < 1e-7, "x = {x}");
        }
        // It falls the whole length sooner than a body would (sqrt 2).
        assert!(time_to_fall(1.0) < 2f64.sqrt());
    }

    #[test]
    fn fall_at_inverts_time_to_fall() {
        for x in [0.0, 0.01, 0.25, 0.5, 0.75, 0.99] {
            assert!((fall_at(time_to_fall(x)) - x).abs() < 1e-12, "x = {x}");
        }
        assert_eq!(fall_at(10.0), 1.0);
    }

    #[test]
    fn the_support_holds_half_the_weight_at_first() {
        assert!((support_tension(0.0) - 0.5).abs() < 1e-15);
        let x = 0.5;
        let expected = (1.0 + x) / 2.0 + speed(x).powi(2) / 4.0;
        assert!((support_tension(x) - expected).abs() < 1e-14);
    }
}
