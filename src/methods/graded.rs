//! Rods graded towards the free end: the chain's method (joint forces, RK4) on N rods whose
//! lengths shrink towards the tip, rod i spanning s_i = 1 − (1 − i/N)^1.5 to s_{i+1}. The whip
//! of a falling string happens in its last few rods; on equal rods the tip's error through it
//! falls only at first order in h, and graded rods resolve it: from 30° they need about 2.6
//! times fewer rods for a tip error of 1e-4 (`docs/measurements.md`).
//!
//! The grading is 1.5, not stronger: at 2 and above the shortest end rods spin at up to 2e4
//! radians a time unit in the whip, and their substeps (each rod's own wave and spin must be
//! resolved) cost more than the rods save. Only releases: a release is straight, so every rod
//! starts at its angle whatever its length.

use super::chain::{self, Chain};
use super::method::Descriptor;
use crate::model::Scene;

/// The exponent of the grading: s_i = 1 − (1 − i/N)^GRADING.
pub const GRADING: f64 = 1.5;

/// The lowest release angle, in degrees, from which the end rods come out of the whip
/// without spinning on: from 10° and below they may go on spinning, out of reach of the
/// adaptive steps and of the cost model. At N = 600 to t = 1.6, from 0° at the tolerance
/// step (k = 1/1920) a step cost 43 000 ns per segment, from 10° to t = 2 at the default step
/// 4 500; from 30°, 206 (`rope run --method graded --segments 600 …`, `docs/physics.md`).
/// `--tolerance` chooses the graded rods from here up only.
pub const SPIN_FREE_FROM: f64 = 20.0;

/// Past [`SPIN_FREE_UNTIL`] the end rods come out of a second whip, near t = 4.8, spinning
/// from below this angle: at the tolerance step a step to t = 5 cost 3 854 ns per segment from
/// 30° at N = 800 (289 to t = 3), 1 290 from 35° at N = 200 (345), at most 544 from 40° to 70°
/// (`docs/measurements.md`). `--tolerance` chooses the graded rods for a longer run from here
/// up only.
pub const SPIN_FREE_LONGER_FROM: f64 = 40.0;

/// The time up to which the graded rods' end rods come out of the whip without spinning from
/// [`SPIN_FREE_FROM`] up.
pub const SPIN_FREE_UNTIL: f64 = 3.0;

/// What the graded rods say of themselves (see [`Descriptor`]): the chain's, but for what
/// the grading changes.
pub const DESCRIPTOR: Descriptor = Descriptor {
    name: "graded",
    limit_meaning: "substeps start: k = C h / sqrt(F_max), h = 1/N (each rod's own wave and spin then add substeps)",
    // `cargo bench --bench step -- graded_step` at N = 1000 (the chain: 169): each rod's own
    // wave sqrt(F_i)/l_i and spin set the substeps, and the short end rods add them in the
    // whip. Left as it was when the chain's rods came to be turned between steps (since, 10
    // to 20 % less: docs/measurements.md), so that `--tolerance` chooses as the committed
    // check measured.
    ns_per_segment_step: 340.0,
    discretization: "graded rods",
    // Its short end rods, once whipped round, spin on and add substeps: from 30° at N = 100
    // over 60 time units, 3 times the chain's cost per step.
    steady_cost: false,
    // The chain's vectors and the rods' lengths.
    bytes_per_segment: chain::DESCRIPTOR.bytes_per_segment + 8,
    colours: ([100, 210, 215], [0, 105, 120]),
    build: |scene, segments, dt| {
        Ok(Box::new(Chain::graded(
            &DESCRIPTOR,
            scene,
            segments,
            dt,
            GRADING,
        )?))
    },
    starts_from: chain::graded_starts_from,
    plannable: |scene, duration| {
        let from = match duration <= SPIN_FREE_UNTIL {
            true => SPIN_FREE_FROM,
            false => SPIN_FREE_LONGER_FROM,
        };
        matches!(scene, Scene::Release { angle_deg } if *angle_deg >= from)
    },
    ..chain::DESCRIPTOR
};
