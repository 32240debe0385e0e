//! The converged solution a study measures errors against: a method of known order at a fine N,
//! extrapolated in N, with its own error estimated.

use super::grid::{Row, SHAPE_POINTS, Status, run_cell};
use crate::methods::MethodKind;
use crate::model::{Point, Scene};
use rayon::prelude::*;

/// A converged solution the study trusts, and how far it can be trusted.
#[derive(Clone, Debug)]
pub struct Reference {
    pub tip: Point,
    pub shape: Vec<Point>,
    /// |Richardson correction| in N: the error left by the finest N, estimated.
    pub error_in_h: f64,
    /// Change of the finest run when its time step is halved.
    pub error_in_k: f64,
    pub description: String,
}

impl Reference {
    /// The larger of the two estimates: errors below it are not resolved.
    pub fn error_estimate(&self) -> f64 {
        self.error_in_h.max(self.error_in_k)
    }
}

/// The reference's runs, as (method, N, k): [`MethodKind::REFERENCE`] at `finest` segments
/// and its default step, at `finest / 2` and its default step, and at `finest` with half the
/// step.
pub fn reference_runs(finest: usize) -> [(MethodKind, usize, f64); 3] {
    let method = MethodKind::REFERENCE;
    let (coarse, dt) = (finest / 2, method.default_dt(finest));
    [
        (method, finest, dt),
        (method, coarse, method.default_dt(coarse)),
        (method, finest, dt / 2.0),
    ]
}

/// The reference: [`MethodKind::REFERENCE`] at `finest` and `finest / 2` segments,
/// extrapolated in N by Richardson (x + (x − x_half) / (2^p − 1), p its order: 2 for the
/// chain), with the time step checked by halving it at the finest N.
pub fn reference(scene: &Scene, duration: f64, finest: usize) -> anyhow::Result<Reference> {
    let run = |method: MethodKind, n: usize, dt: f64| -> anyhow::Result<(Point, Vec<Point>)> {
        let row = run_cell(scene, duration, method, n, dt);
        match (row.status, row.tip, row.shape) {
            (Status::Ok, Some(tip), Some(shape)) => Ok((tip, shape)),
            (status, ..) => {
                anyhow::bail!("the reference run at N = {n}, k = {dt:e} failed: {status:?}")
            }
        }
    };
    let runs = reference_runs(finest);
    let [(method, _, dt), (_, coarse_n, _), _] = runs;
    let runs: Vec<_> = runs
        .into_par_iter()
        .map(|(method, n, dt)| run(method, n, dt))
        .collect::<anyhow::Result<_>>()?;
    let [(tip_f, shape_f), (tip_c, shape_c), (tip_k, _)]: [(Point, Vec<Point>); 3] = runs
        .try_into()
        .map_err(|_| anyhow::anyhow!("three reference runs expected"))?;
    // Richardson in h: x + (x − x_half) / (2^p − 1), p the method's order.
    let order = f64::from(method.descriptor().order_in_h);
    let extrapolate = |f: Point, c: Point| f + (f - c) / (2f64.powf(order) - 1.0);
    let tip = extrapolate(tip_f, tip_c);
    let shape: Vec<Point> = shape_f
        .iter()
        .zip(&shape_c)
        .map(|(&f, &c)| extrapolate(f, c))
        .collect();
    Ok(Reference {
        tip,
        shape,
        error_in_h: (tip - tip_f).norm(),
        error_in_k: (tip_k - tip_f).norm(),
        description: format!(
            "{method} method, Richardson extrapolation (order {order}) from N = {coarse_n} and {finest}, k = {dt:e}"
        ),
    })
}

/// Fills in each row's errors against the reference.
pub fn measure_errors(rows: &mut [Row], reference: &Reference) {
    for row in rows {
        if let (Some(tip), Some(shape)) = (row.tip, &row.shape) {
            row.tip_error = Some((tip - reference.tip).norm());
            let sum: f64 = shape
                .iter()
                .zip(&reference.shape)
                .map(|(a, b)| (a - b).norm_squared())
                .sum();
            row.shape_error = Some((sum / SHAPE_POINTS as f64).sqrt());
        }
    }
}
