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
/// each cosine carried along the instants by the three-term recurrence. One chain of it,
/// cos((i + 1)θ) = 2 cos θ cos iθ − cos((i − 1)θ), waits a multiply and a subtract at every
/// instant, whatever the processor could do beside it. So the instants go [`PHASES`] at a
/// time: those of one phase (i ≡ p mod [`PHASES`]) form a chain of their own,
/// cos((i + P)θ) = 2 cos Pθ cos iθ − cos((i − P)θ), and the chains step side by side, the
/// waves [`LANES`] abreast, each group's cosines in registers, adding into a sum per instant
/// (a planning pass runs this a dozen times over 9 000 instants, and costs as much as the run
/// it plans at small N).
fn largest_difference(a: &[(f64, f64)], b: &[(f64, f64)], instants: usize) -> f64 {
    let dt = 1.0 / RATE;
    let signed: Vec<(f64, f64)> = a
        .iter()
        .map(|&(w, b)| (w, b))
        .chain(b.iter().map(|&(w, b)| (w, -b)))
        .collect();
    // Block j holds the sums at instants j·PHASES + p; the last block's extra instants are
    // past the run, and left out of the result.
    let mut sums = vec![[0.0; PHASES]; (instants + 1).div_ceil(PHASES)];
    for group in signed.chunks(LANES) {
        // A lane left empty weighs nothing (and its cosines stay at 1).
        let mut weight = [0.0; LANES];
        let mut two_cos = [2.0; LANES];
        // Each phase p's cosine now, at instant p, and one chain step before (p − PHASES).
        let mut now = [[1.0; LANES]; PHASES];
        let mut previous = [[1.0; LANES]; PHASES];
        for (lane, &(w, b)) in group.iter().enumerate() {
            let angle = w * dt;
            weight[lane] = b;
            two_cos[lane] = 2.0 * (PHASES as f64 * angle).cos();
            for p in 0..PHASES {
                now[p][lane] = (p as f64 * angle).cos();
                previous[p][lane] = ((p as f64 - PHASES as f64) * angle).cos();
            }
        }
        for block in &mut sums {
            for p in 0..PHASES {
                let mut here = 0.0;
                for lane in 0..LANES {
                    here += weight[lane] * now[p][lane];
                    let next = two_cos[lane] * now[p][lane] - previous[p][lane];
                    previous[p][lane] = now[p][lane];
                    now[p][lane] = next;
                }
                block[p] += here;
            }
        }
    }
    sums.iter()
        .flatten()
        .take(instants + 1)
        .fold(0.0, |worst: f64, sum| worst.max(sum.abs()))
}

/// How many waves [`largest_difference`] steps abreast.
const LANES: usize = 2;

/// How many chains of instants [`largest_difference`] steps side by side: at two waves abreast
/// and four phases, a pass is 1.5 to 1.7 times as fast as the four waves abreast of one chain
/// it replaced (one, ten and seventeen waves over 9 000 instants).
const PHASES: usize = 4;

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

#[cfg(test)]
mod tests {
    use super::*;

    /// The recurrence, its waves two abreast and its instants in four chains, reads what the
    /// cosines summed directly at every instant read: five waves on one side, two on the
    /// other (four groups, one with a lane left empty), over 9 001 instants (the last block
    /// of four holds one).
    #[test]
    fn the_largest_difference_is_that_of_the_cosines_summed_at_every_instant() {
        let a = [
            (2.0, 0.05),
            (5.3, -2e-3),
            (9.1, 4e-4),
            (13.7, 1e-4),
            (17.0, -3e-5),
        ];
        let b = [(2.01, 0.05), (5.2, 1e-3)];
        let direct = |instants: usize| {
            (0..=instants)
                .map(|i| {
                    let t = i as f64 / RATE;
                    let sum = |waves: &[(f64, f64)]| -> f64 {
                        waves.iter().map(|&(w, b)| b * (w * t).cos()).sum()
                    };
                    (sum(&a) - sum(&b)).abs()
                })
                .fold(0.0, f64::max)
        };
        for instants in [0, 1, 2, 3, 4, 5, 9000] {
            let (carried, direct) = (largest_difference(&a, &b, instants), direct(instants));
            // The recurrence's round-off over 9 000 instants, about 1e-13 here (9e-12 when
            // each wave was one chain): a billionth of the smallest tolerance the check asks.
            assert!(
                (carried - direct).abs() <= 1e-10,
                "{instants} instants: {carried:e} against {direct:e}"
            );
        }
        let direct = direct(9000);
        assert!(direct > 1e-3, "the waves drift apart: {direct:e}");
    }

    /// A run of a few instants, whose last block of four lies part past its end: its last
    /// instant is read, and none past it. Two waves that start together and part faster at
    /// every instant, so that the largest difference is always the last instant's.
    #[test]
    fn the_largest_difference_ends_at_the_runs_last_instant() {
        let (a, b) = ([(300.0, 1.0)], [(600.0, 1.0)]);
        for instants in 0..=9 {
            let t = instants as f64 / RATE;
            let last = ((300.0 * t).cos() - (600.0 * t).cos()).abs();
            let carried = largest_difference(&a, &b, instants);
            assert!(
                (carried - last).abs() <= 1e-12,
                "{instants} instants: {carried:e} against {last:e} at the last"
            );
        }
    }
}
