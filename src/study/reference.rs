//! The converged solution a study measures errors against: a method of known order at a fine N,
//! extrapolated in N, with its own error estimated, kept at every step so that a run's tip
//! can be measured against it at every frame.

use super::grid::{FRAMES_PER_UNIT, Row, shape};
use super::progress::Progress;
use super::trajectory::{Kept, Trajectory, frame_times};
use crate::methods::MethodKind;
use crate::model::{Point, Scene};
use rayon::prelude::*;

/// A converged solution the study trusts, and how far it can be trusted.
#[derive(Clone, Debug)]
pub struct Reference {
    /// The tip at the final time.
    pub tip: Point,
    /// The shape (s = 0, 0.1, …, 1) at the final time.
    pub shape: Vec<Point>,
    /// The tip at every step of the finest run, extrapolated: what a run's frames are
    /// measured against.
    pub path: Trajectory,
    /// |Richardson correction| in N, the largest over the frames: the error left by the
    /// finest N, estimated.
    pub error_in_h: f64,
    /// The largest change of the finest run's tip over the frames when its time step is
    /// halved.
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
/// chain) at every step of the finest run, with the time step checked by halving it at the
/// finest N. Its own errors are the largest over the frames. `progress` may stop its runs
/// partway ([`super::Stopped`]).
pub fn reference(
    scene: &Scene,
    duration: f64,
    finest: usize,
    progress: &impl Progress,
) -> anyhow::Result<Reference> {
    use anyhow::Context as _;
    let runs = reference_runs(finest);
    let [(method, _, dt), (_, coarse_n, _), _] = runs;
    let kept: Vec<Kept> = runs
        .into_par_iter()
        .map(|(method, n, dt)| {
            Trajectory::keep_stoppable(scene, method, n, dt, duration, progress)
                .context("the reference")
        })
        .collect::<anyhow::Result<_>>()?;
    let [fine, coarse, halved]: [Kept; 3] = kept
        .try_into()
        .map_err(|_| anyhow::anyhow!("three reference runs expected"))?;
    // Richardson in h: x + (x − x_half) / (2^p − 1), p the method's order.
    let order = f64::from(method.descriptor().order_in_h);
    let extrapolate = |f: Point, c: Point| f + (f - c) / (2f64.powf(order) - 1.0);
    let path = Trajectory::new(
        dt,
        fine.trajectory
            .tips()
            .iter()
            .enumerate()
            .map(|(i, &f)| extrapolate(f, coarse.trajectory.at(i as f64 * dt)))
            .collect(),
    );
    // Its own errors, the largest over the frames a study measures its runs at.
    let frames = frame_times(duration, FRAMES_PER_UNIT);
    let (shape_f, shape_c) = (shape(&fine.angles), shape(&coarse.angles));
    Ok(Reference {
        tip: extrapolate(fine.tip, coarse.tip),
        shape: shape_f
            .iter()
            .zip(&shape_c)
            .map(|(&f, &c)| extrapolate(f, c))
            .collect(),
        error_in_h: path.largest_gap(&fine.trajectory, &frames),
        error_in_k: halved.trajectory.largest_gap(&fine.trajectory, &frames),
        path,
        description: format!(
            "{method} method, Richardson extrapolation (order {order}) from N = {coarse_n} and {finest}, k = {dt:e}"
        ),
    })
}

/// Fills in each row's errors against the reference: the tip's at every frame and at the
/// final time, the shape's at the final time.
pub fn measure_errors(rows: &mut [Row], reference: &Reference) {
    for row in rows {
        if let (Some(tip), Some(shape)) = (row.tip, &row.shape) {
            row.final_tip_error = Some((tip - reference.tip).norm());
            row.tip_error = row
                .frame_tips
                .iter()
                .map(|&(t, tip)| (tip - reference.path.at(t)).norm())
                .reduce(f64::max);
            let sum: f64 = shape
                .iter()
                .zip(&reference.shape)
                .map(|(a, b)| (a - b).norm_squared())
                .sum();
            row.shape_error = Some((sum / shape.len().max(1) as f64).sqrt());
        }
    }
}
