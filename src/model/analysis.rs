//! Measurements on sampled series: oscillation periods from zero crossings, and the peaks of
//! a response sampled over frequency.

/// The period of an oscillation about zero sampled as `(t, x)` pairs, from its zero crossings
/// (located by linear interpolation): successive crossings are half a period apart, and the
/// mean spacing between the first and the last is used. `None` with fewer than three
/// crossings (one full period).
pub fn period_from_zero_crossings(samples: impl IntoIterator<Item = (f64, f64)>) -> Option<f64> {
    let mut crossings = ZeroCrossings::default();
    for (t, x) in samples {
        crossings.push(t, x);
    }
    crossings.period()
}

/// The zero crossings of a series taken one sample at a time, in constant memory: the first,
/// the last and how many, which is all [`period_from_zero_crossings`] needs.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ZeroCrossings {
    last: Option<(f64, f64)>,
    first: Option<f64>,
    latest: f64,
    count: u64,
}

impl ZeroCrossings {
    /// Takes the sample `x` at time `t` (after every earlier one).
    pub fn push(&mut self, t: f64, x: f64) {
        if let Some((t0, x0)) = self.last
            && ((x0 < 0.0 && x >= 0.0) || (x0 > 0.0 && x <= 0.0))
        {
            let crossing = t0 + (t - t0) * x0 / (x0 - x);
            self.first.get_or_insert(crossing);
            self.latest = crossing;
            self.count += 1;
        }
        self.last = Some((t, x));
    }

    /// Twice the mean spacing of the crossings: the period, from three crossings or more.
    pub fn period(&self) -> Option<f64> {
        let first = self.first.filter(|_| self.count >= 3)?;
        Some(2.0 * (self.latest - first) / (self.count - 1) as f64)
    }
}

/// The peaks of a positive response sampled as `(x, y)` pairs in increasing x: each sample
/// higher than both its neighbours, its place refined by the parabola through log y at the
/// three (a resonance's peak is near a parabola in log y; the refinement stays within the
/// neighbours). Returns `(x, y)` of each peak, in increasing x.
pub fn peaks(samples: &[(f64, f64)]) -> Vec<(f64, f64)> {
    samples
        .windows(3)
        .filter(|w| w[1].1 > w[0].1 && w[1].1 > w[2].1 && w.iter().all(|p| p.1 > 0.0))
        .map(|w| {
            let [(x0, y0), (x1, y1), (x2, y2)] = [w[0], w[1], w[2]];
            let (l0, l1, l2) = (y0.ln(), y1.ln(), y2.ln());
            // The vertex of the parabola through the three points (x unevenly spaced too).
            let d01 = (l1 - l0) / (x1 - x0);
            let d12 = (l2 - l1) / (x2 - x1);
            let curvature = (d12 - d01) / (x2 - x0);
            let vertex = if curvature < 0.0 {
                0.5 * (x0 + x1) - d01 / (2.0 * curvature)
            } else {
                x1
            };
            (vertex.clamp(x0, x2), y1)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_peaks_of_two_resonances_sampled_coarsely_are_found_between_the_samples() {
        let response =
            |x: f64| 1.0 / ((x - 1.23).powi(2) + 0.01) + 1.0 / ((x - 2.71).powi(2) + 0.01);
        let samples: Vec<(f64, f64)> = (0..40)
            .map(|i| {
                let x = 0.2 + 0.1 * i as f64;
                (x, response(x))
            })
            .collect();
        let found = peaks(&samples);
        assert_eq!(found.len(), 2, "{found:?}");
        assert!((found[0].0 - 1.23).abs() < 0.02, "{found:?}");
        assert!((found[1].0 - 2.71).abs() < 0.02, "{found:?}");
    }

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
