//! A mode's tip error known before any run: the linear theory of the rods' small oscillations.
//!
//! Hanging near the vertical, N equal rods (mass h, length h, moment of inertia h³/12 about
//! the centre, as [`crate::methods::chain`] models them) at small angles α_j from the vertical
//! obey M α̈ + K α = 0. The rod's centre moves sideways by x_i = Σ_{j<i} h α_j + (h/2) α_i, so
//! M = h CᵀC + (h³/12) I with C_ij = h (j < i), h/2 (j = i); gravity lifts rod j's centre and
//! everything below it by h α_j²/2 (half that for itself), so K = diag(h (1 − s_j)) with s_j
//! the rod's centre (g = 1, the string of unit length and mass). Started from the string's
//! mode shape sampled at the centres (as [`Scene::initial_angles`] starts it), the tip
//! x_N(t) = Σ_j h α_j(t) is a sum over the rods' own modes, and the string's tip is
//! A cos ωt (eq. of D. Bernoulli's mode, J₀(2ω) = 0). Their largest difference over every
//! 1/3 000 of [0, T] is the rods' error in h, the one a `--tolerance` run must bound.
//!
//! Measured against the chain itself (its tip against the chain at N = 1 024, at every frame
//! of 300 a unit, to t = 3 and 10), the theory's error is 0.93 to 1.19 of the chain's at
//! N = 4 … 32, for modes 1 and 2 up to a tip amplitude of 0.1 (`cargo run --release --example
//! mode_theory`). Past that the swing is no longer small: mode 2 at 0.2 errs by 1.55 times the
//! theory, mode 3 at 0.05 by 1.4, mode 4 by 3.7 to 8. There the theory serves nothing, and the
//! pilots measure the scene as before.

use crate::methods::MethodKind;
use crate::model::{Scene, bessel};
use crate::run::estimate::TipBound;
use nalgebra::{DMatrix, DVector};

/// The largest tip amplitude the theory serves ([`serves`]).
pub const LARGEST_AMPLITUDE: f64 = 0.1;

/// The highest mode the theory serves ([`serves`]).
pub const HIGHEST_MODE: u32 = 2;

/// The longest run the theory was measured over ([`serves`]).
pub const LONGEST_DURATION: f64 = 10.0;

/// The most rods the theory is worked out for: its cost grows as N³ (about 1 ms at N = 128).
pub const MOST_SEGMENTS: usize = 1024;

/// Instants per time unit at which the tips are compared: every 1/3 000, as a tolerance
/// is judged.
pub const RATE: f64 = 3000.0;

/// Whether the theory is of `method`'s rods: equal rods, as the chain, RATTLE and the
/// midpoint rule step them (at their tolerance steps their error in k is negligible beside h's).
pub fn of_rods(method: MethodKind) -> bool {
    method.descriptor().discretization == "rods"
}

/// Whether the theory serves `scene` to `duration`: a mode up to [`HIGHEST_MODE`], its tip
/// amplitude at most [`LARGEST_AMPLITUDE`], for at most [`LONGEST_DURATION`].
pub fn serves(scene: &Scene, duration: f64) -> bool {
    match *scene {
        Scene::Mode { number, amplitude } => {
            (1..=HIGHEST_MODE).contains(&number)
                && amplitude.abs() <= LARGEST_AMPLITUDE
                && (0.0..=LONGEST_DURATION).contains(&duration)
        }
        _ => false,
    }
}

/// The largest sideways distance, over every 1/[`RATE`] of [0, `duration`], between the tip of
/// `segments` equal rods started in mode `number` of tip amplitude `amplitude` and the string's
/// tip, by linear theory; `None` for no rods.
pub fn tip_error(number: u32, amplitude: f64, segments: usize, duration: f64) -> Option<f64> {
    let rods = tip_waves(number, amplitude, segments)?;
    let string = [(bessel::mode_frequency(number), amplitude)];
    worst_gap(&rods, &string, duration)
}

/// What a run's live estimate of the same will read at most ([`TipBound`]): the largest
/// distance between the tips of `segments` rods and of its shadow's N/2, over every
/// 1/[`RATE`], times the bound's factor; `None` for fewer than two rods.
pub fn live_bound(
    number: u32,
    amplitude: f64,
    segments: usize,
    duration: f64,
    bound: TipBound,
) -> Option<f64> {
    let shadow = segments / 2;
    let gap = worst_gap(
        &tip_waves(number, amplitude, segments)?,
        &tip_waves(number, amplitude, shadow)?,
        duration,
    )?;
    let ratio = segments as f64 / shadow as f64;
    Some(gap * bound.of_first_order(ratio) / (ratio - 1.0))
}

/// The tip of `segments` equal rods started in mode `number`, as Σ b cos(w t): each of the
/// rods' own modes as (w, b), the most excited first; `None` for no rods.
///
/// With K diagonal, z = K^½ α turns M α̈ + K α = 0 into B z̈ + z = 0, B = K^-½ M K^-½
/// symmetric: its eigenvalues are 1/w², and b = (uᵀ K^-½ h1)(uᵀ K^½ α₀) for each of its
/// eigenvectors u.
fn tip_waves(number: u32, amplitude: f64, segments: usize) -> Option<Vec<(f64, f64)>> {
    if segments == 0 {
        return None;
    }
    let n = segments;
    let h = 1.0 / n as f64;
    let omega = bessel::mode_frequency(number);
    let centre = |j: usize| (j as f64 + 0.5) * h;
    // The start: the string's slope dx/ds = A ω J₁(2ω r)/r at each centre, r = sqrt(1 − s).
    let start = |j: usize| {
        let r = (1.0 - centre(j)).sqrt();
        amplitude * omega * bessel::j1(2.0 * omega * r) / r
    };
    // K = diag(h (1 − s_j)): rod j lifts its centre and everything below it.
    let root_k: Vec<f64> = (0..n).map(|j| (h * (1.0 - centre(j))).sqrt()).collect();
    // M = h CᵀC + (h³/12) I: (CᵀC)_jk = Σ_i C_ij C_ik over the rods i at or below both, whole
    // below the lower of the two, by half at it.
    let b = DMatrix::from_fn(n, n, |j, k| {
        let high = j.max(k);
        let below = (n - 1 - high) as f64 * h * h;
        let own = match j == k {
            true => 0.25 * h * h + h * h / 12.0,
            false => 0.5 * h * h,
        };
        h * (below + own) / (root_k[j] * root_k[k])
    });
    let eigen = b.symmetric_eigen();
    let z0 = DVector::from_fn(n, |j, _| root_k[j] * start(j));
    let tip = DVector::from_fn(n, |j, _| h / root_k[j]);
    let mut waves: Vec<(f64, f64)> = (0..n)
        .map(|k| {
            let u = eigen.eigenvectors.column(k);
            let frequency = eigen.eigenvalues[k].max(f64::MIN_POSITIVE).recip().sqrt();
            (frequency, u.dot(&tip) * u.dot(&z0))
        })
        .collect();
    waves.sort_by(|a, b| b.1.abs().total_cmp(&a.1.abs()));
    Some(waves)
}

/// The largest |Σ_a b cos(w t) − Σ_b b cos(w t)| over every 1/[`RATE`] of [0, `duration`]. Each
/// sum's least excited waves are left out, their weights |b| added to the result instead (on
/// the safe side), as long as they come to at most a hundredth of the gap between the two most
/// excited alone. `None` for an empty sum or an endless run.
fn worst_gap(a: &[(f64, f64)], b: &[(f64, f64)], duration: f64) -> Option<f64> {
    if a.is_empty() || b.is_empty() || !duration.is_finite() {
        return None;
    }
    let instants = (duration.max(0.0) * RATE).ceil() as usize;
    let first = largest_difference(&a[..1], &b[..1], instants);
    let mut dropped = 0.0;
    let kept = |waves: &[(f64, f64)], dropped: &mut f64| {
        let mut kept = waves.len();
        while kept > 1 && *dropped + waves[kept - 1].1.abs() <= 0.005 * first {
            *dropped += waves[kept - 1].1.abs();
            kept -= 1;
        }
        kept
    };
    let (in_a, in_b) = (kept(a, &mut dropped), kept(b, &mut dropped));
    Some(largest_difference(&a[..in_a], &b[..in_b], instants) + dropped)
}

/// The largest of |Σ_a b cos(w t) − Σ_b b cos(w t)| at t = i/[`RATE`], i = 0 … `instants`,
/// each cosine carried from one instant to the next by cos((i + 1)θ) = 2 cos θ cos iθ −
/// cos((i − 1)θ).
fn largest_difference(a: &[(f64, f64)], b: &[(f64, f64)], instants: usize) -> f64 {
    let dt = 1.0 / RATE;
    // Each wave as (weight, 2 cos θ, cos iθ, cos (i − 1)θ), the second sum's weights negated.
    let wave = |w: f64, b: f64| [b, 2.0 * (w * dt).cos(), 1.0, (w * dt).cos()];
    let mut waves: Vec<[f64; 4]> = a
        .iter()
        .map(|&(w, b)| wave(w, b))
        .chain(b.iter().map(|&(w, b)| wave(w, -b)))
        .collect();
    let mut worst: f64 = 0.0;
    for _ in 0..=instants {
        let mut sum = 0.0;
        for wave in &mut waves {
            sum += wave[0] * wave[2];
            let next = wave[1] * wave[2] - wave[3];
            wave[3] = wave[2];
            wave[2] = next;
        }
        worst = worst.max(sum.abs());
    }
    worst
}

/// What the theory says a tolerance needs: the rods' error at two segment counts a doubling
/// apart, `fewer` past the tolerance (or the fewest a run takes) and `more` within it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bracket {
    pub fewer: (usize, f64),
    pub more: (usize, f64),
}

impl Bracket {
    /// The order the error falls at between the two, log₂ of their ratio.
    pub fn order(&self) -> f64 {
        (self.fewer.1 / self.more.1).log2()
    }
}

/// The two segment counts, doubling from `fewest`, between which the theory's error of
/// `scene` to `duration` times `safety` falls within `tolerance` (where even `fewest` holds it,
/// `fewest` and twice it); `None` where the theory does not serve the scene ([`serves`]) or
/// none up to [`MOST_SEGMENTS`] holds it.
pub fn bracket(
    scene: &Scene,
    duration: f64,
    tolerance: f64,
    safety: f64,
    fewest: usize,
) -> Option<Bracket> {
    let Scene::Mode { number, amplitude } = *scene else {
        return None;
    };
    if !serves(scene, duration) {
        return None;
    }
    let error = |n: usize| tip_error(number, amplitude, n, duration);
    let mut fewer = (fewest.max(1), error(fewest.max(1))?);
    if safety * fewer.1 <= tolerance {
        let more = (2 * fewer.0, error(2 * fewer.0)?);
        return Some(Bracket { fewer, more });
    }
    loop {
        let n = 2 * fewer.0;
        if n > MOST_SEGMENTS {
            return None;
        }
        let more = (n, error(n)?);
        if safety * more.1 <= tolerance {
            return Some(Bracket { fewer, more });
        }
        fewer = more;
    }
}
