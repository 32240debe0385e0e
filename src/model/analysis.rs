//! Measurements on sampled time series: oscillation periods from zero crossings.

/// The period of an oscillation about zero sampled as `(t, x)` pairs, from its zero crossings
/// (located by linear interpolation): successive crossings are half a period apart, and the
/// mean spacing between the first and the last is used. `None` with fewer than three
/// crossings (one full period).
pub fn period_from_zero_crossings(samples: impl IntoIterator<Item = (f64, f64)>) -> Option<f64> {
    let mut crossings = Vec::new();
    let mut last: Option<(f64, f64)> = None;
    for (t, x) in samples {
        if let Some((t0, x0)) = last
            && ((x0 < 0.0 && x >= 0.0) || (x0 > 0.0 && x <= 0.0))
        {
            crossings.push(t0 + (t - t0) * x0 / (x0 - x));
        }
        last = Some((t, x));
    }
    match crossings.as_slice() {
        [first, .., last] if crossings.len() >= 3 => {
            Some(2.0 * (last - first) / (crossings.len() - 1) as f64)
        }
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn period_of_a_sampled_cosine() {
        let w = 1.2;
        let samples = (0..2000).map(|i| {
            let t = i as f64 * 0.01;
            (t, (w * t).cos())
        });
        let period = period_from_zero_crossings(samples).unwrap();
        assert!((period - std::f64::consts::TAU / w).abs() < 1e-4);
    }
}
