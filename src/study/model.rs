//! The error and cost model fitted to the study, and the rule `rope run --tolerance` uses to
//! model a scene with no more than it needs.
//!
//! Tip error at the final time ≈ C h^p per method, fitted by least squares over the study's
//! converged-in-k runs (`rope study` prints the fit; README, "Modelling no more than a scene
//! needs"). Cost ≈ c × N × steps per method (ns per segment-step from `cargo bench`).

use super::{Row, Status};
use crate::method::MethodKind;

/// Tip error ≈ `constant` · h^`order`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ErrorModel {
    pub constant: f64,
    pub order: f64,
}

impl ErrorModel {
    /// Predicted tip error at `segments`.
    pub fn predict(&self, segments: usize) -> f64 {
        self.constant * (1.0 / segments as f64).powf(self.order)
    }

    /// Fewest segments whose predicted error is at most `tolerance`.
    pub fn segments_for(&self, tolerance: f64) -> usize {
        let h = (tolerance / self.constant).powf(1.0 / self.order);
        (1.0 / h).ceil() as usize
    }
}

/// The fit committed with the code: the 30° release at t = 1, from
/// `rope study --out assets/study` (its printed "error model" lines).
pub fn committed(method: MethodKind) -> ErrorModel {
    match method {
        MethodKind::Seed => ErrorModel {
            constant: 1.04,
            order: 1.00,
        },
        MethodKind::Chain => ErrorModel {
            constant: 0.079,
            order: 1.97,
        },
    }
}

/// Measured cost of one segment-step, in ns (`cargo bench --bench step`, N = 1000; the
/// chain's includes its four RK4 stages).
pub fn ns_per_segment_step(method: MethodKind) -> f64 {
    match method {
        MethodKind::Seed => 10.2,
        MethodKind::Chain => 170.0,
    }
}

/// Fits C h^p to the tip errors of the `ok` runs of `method` with N ≥ `min_segments`, taking
/// at each N the run with the smallest time step (so that the error is the spatial one).
pub fn fit(rows: &[Row], method: MethodKind, min_segments: usize) -> Option<ErrorModel> {
    let mut points: Vec<(f64, f64)> = Vec::new();
    let mut segments: Vec<usize> = rows
        .iter()
        .filter(|r| r.method == method && r.segments >= min_segments)
        .map(|r| r.segments)
        .collect();
    segments.sort_unstable();
    segments.dedup();
    for n in segments {
        let best = rows
            .iter()
            .filter(|r| r.method == method && r.segments == n && r.status == Status::Ok)
            .filter_map(|r| r.tip_error.map(|e| (r.dt, e)))
            .min_by(|a, b| a.0.total_cmp(&b.0));
        if let Some((_, e)) = best.filter(|(_, e)| *e > 0.0) {
            points.push(((1.0 / n as f64).ln(), e.ln()));
        }
    }
    if points.len() < 2 {
        return None;
    }
    let m = points.len() as f64;
    let (mx, my) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / m, b + y / m));
    let sxy: f64 = points.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = points.iter().map(|(x, _)| (x - mx) * (x - mx)).sum();
    let order = sxy / sxx;
    Some(ErrorModel {
        constant: (my - order * mx).exp(),
        order,
    })
}

/// What the tolerance rule chose.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Choice {
    pub method: MethodKind,
    pub segments: usize,
    pub dt: f64,
    pub predicted_error: f64,
    /// Predicted CPU seconds for `duration`.
    pub predicted_seconds: f64,
}

/// The cheapest method, N and k whose predicted tip error is at most `tolerance`, among the
/// methods that can start from `scene`. Each method's N comes from its error model (with a
/// safety factor of 2), its k is the method's default for that N.
pub fn choose(tolerance: f64, duration: f64, scene: &crate::scene::Scene) -> Option<Choice> {
    const SAFETY: f64 = 2.0;
    MethodKind::ALL
        .iter()
        .filter_map(|&method| {
            let model = committed(method);
            let segments = model.segments_for(tolerance / SAFETY).max(4);
            let dt = method.default_dt(segments);
            method.build(scene, segments, dt).ok()?;
            let steps = (duration / dt).round().max(1.0);
            Some(Choice {
                method,
                segments,
                dt,
                predicted_error: model.predict(segments),
                predicted_seconds: ns_per_segment_step(method) * 1e-9 * segments as f64 * steps,
            })
        })
        .min_by(|a, b| a.predicted_seconds.total_cmp(&b.predicted_seconds))
}
