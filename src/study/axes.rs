//! The ranges of the studies' chart axes, for any data: none, one point, or values all
//! equal. A chart of nothing draws empty axes; it never asks the plotting library for an
//! infinite or empty range (an infinite one made it compute ticks for ever).

use std::ops::Range;

/// A log axis covering the positive, finite `values`, padded by a factor of 2 each way;
/// 1e-6 to 1 when there are none.
pub fn log_range(values: impl IntoIterator<Item = f64>) -> Range<f64> {
    match bounds(values.into_iter().filter(|v| *v > 0.0)) {
        Some((lo, hi)) => lo / 2.0..hi * 2.0,
        None => 1e-6..1.0,
    }
}

/// A linear axis covering the finite `values`, padded by 5 % of their span each way. Values
/// all equal (to 12 digits) get an axis a tenth of their size each way (±1 about 0); none get
/// 0 to 1.
pub fn linear_range(values: impl IntoIterator<Item = f64>) -> Range<f64> {
    let Some((lo, hi)) = bounds(values.into_iter()) else {
        return 0.0..1.0;
    };
    let magnitude = lo.abs().max(hi.abs());
    if hi - lo <= 1e-12 * magnitude {
        let half = if magnitude > 0.0 {
            0.1 * magnitude
        } else {
            1.0
        };
        let middle = 0.5 * (lo + hi);
        return middle - half..middle + half;
    }
    let pad = 0.05 * (hi - lo);
    lo - pad..hi + pad
}

/// The least and the greatest of the finite `values`, if any.
fn bounds(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    values
        .filter(|v| v.is_finite())
        .fold(None, |seen, v| match seen {
            None => Some((v, v)),
            Some((lo, hi)) => Some((f64::min(lo, v), f64::max(hi, v))),
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn usable(r: &Range<f64>) -> bool {
        r.start.is_finite() && r.end.is_finite() && r.start < r.end
    }

    #[test]
    fn no_data_gives_finite_axes() {
        assert!(usable(&linear_range([])));
        assert!(usable(&log_range([])));
        assert!(usable(&linear_range([f64::NAN, f64::INFINITY])));
        assert!(usable(&log_range([0.0, -1.0, f64::NAN])));
    }

    #[test]
    fn one_point_sits_inside_its_axes() {
        for v in [0.0, 1.0, -3.5, 1e6, 2.5e-9] {
            let r = linear_range([v]);
            assert!(usable(&r) && r.start < v && v < r.end, "{v}: {r:?}");
        }
        let r = log_range([3e-4]);
        assert!(usable(&r) && r.start < 3e-4 && 3e-4 < r.end);
    }

    #[test]
    fn equal_values_get_room_and_large_ones_do_not_collapse() {
        let r = linear_range([1e6, 1e6, 1e6]);
        assert!(usable(&r) && r.end - r.start >= 1e5, "{r:?}");
        let r = linear_range([0.99, 0.99 + 1e-15]);
        assert!(r.end - r.start > 0.01, "{r:?}");
    }

    #[test]
    fn a_spread_is_padded_by_a_twentieth() {
        let r = linear_range([1.0, 3.0]);
        assert!((r.start - 0.9).abs() < 1e-12 && (r.end - 3.1).abs() < 1e-12);
    }
}
