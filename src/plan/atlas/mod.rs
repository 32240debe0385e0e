//! The release atlas: the committed error model of a release, per release angle.
//!
//! A method's one error law ([`law`](crate::plan::error_model::law)) is
//! the worst of six scenes up to large N: the horizontal release's whip, whose error constant
//! stays near 0.45/N. From most other angles the rods' worst tip error to t = 3 is far from
//! one law: its constant rises and falls with N by up to a factor of 2 (from 30° it falls from
//! 0.42/N at N = 64 to 0.21/N at N = 400; from 80° it grows from 0.11/N at N = 16 to 0.20/N
//! at N = 200), and the pilots, at N ≤ 64, see only the start of it. The atlas is that error
//! measured: the chain at its tolerance step from each release angle 0°, 10°, …, 90° at
//! N = 16 … 566, against the tolerance check's committed references, else a reference computed
//! as the check computes one (`scripts/release-atlas.sh`, which writes
//! `assets/release-atlas/atlas.csv`, read here at build time). Each worst error is the largest
//! at every 1/3 000 of a time unit, whatever the frames (`tolerance_check::measure`): a whip's
//! error peak is narrower than a frame, and at 60 frames a unit the atlas read up to seven
//! times less than the truth. So is the graded rods' atlas to t = 5.
//!
//! At an angle the atlas measured (one of its own, or a held-out one), a tolerance may be met by an
//! N it measured there: the fewest whose bound (the measured error plus its reference's own) holds
//! it, against a reference that could judge it (its own error at most a tenth of the tolerance, as
//! the tolerance check asks), with no margin, since nothing is interpolated. Otherwise, and
//! wherever it asks fewer segments, for an angle between two of the atlas's the larger of their two
//! errors at each N is taken, times a margin measured at the held-out angles 5°, 15°, …, 85°: the
//! largest ratio of a held-out angle's error to that of its two neighbours (where its reference is
//! too coarse to bound its error, what the error is at least: the measured error less the
//! reference's own). The neighbours' errors it reads are bounds (the measured error plus its
//! reference's own) against references that could judge the tolerance, as the angle's own row and
//! the envelope read them; the margin, a ratio, reads only errors at least ten times their
//! references' own (a reference's own error grows a bound's constant with N: the untrusted
//! bounds are read only as far as a choice needs them). Between the atlas's N, the error is
//! taken as first order from the largest constant (bound × N) at that N and above.
//! Between the atlas's first and last angles, a tolerance may also be met by an N where every
//! angle was measured: the largest bound among them all (their envelope) times how far one angle
//! strays above all the others there at most (the envelope's margin, each angle left out in turn),
//! wherever that asks fewer segments than the neighbours' law. Two neighbours may dip together at
//! one N (from 30° and 40° at N = 1 131 the graded rods err by 1.8e-5, 35° between them by
//! 6.6e-5): the neighbours' margin then grows with the dip, where the envelope's does not.
//! The atlas serves only what it measured: the rods, a release, runs to t ≤ 3, N ≤ 566 (below
//! 20° 1131; the graded rods' 1600, from 20° to 60° 2263); elsewhere the method's one law
//! stands. The graded rods have a second atlas, to t = 5 from 40° ([`LONGER_WINDOW`],
//! [`LONGER_FROM`]), for runs from t = 3 to 5, where the one law, fitted to t ≤ 3, does not
//! cover the run and the pilots' figure rules instead.

use crate::methods::MethodKind;
use crate::model::Scene;
use crate::plan::error_model::ErrorModel;
use std::sync::OnceLock;

/// The release angles the atlas measures, in degrees below the horizontal.
pub const ATLAS_ANGLES: [f64; 10] = [0.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0, 90.0];

/// The angles measured only to find the margin for angles between the atlas's.
pub const HELD_OUT_ANGLES: [f64; 9] = [5.0, 15.0, 25.0, 35.0, 45.0, 55.0, 65.0, 75.0, 85.0];

/// The segment counts an angle may be measured at (√2 apart from 50 up). The chain's atlas is
/// measured to 566 from 20° up (past it the graded rods are the cheaper), below 20° to 1131,
/// the graded rods' to 1600.
pub const SEGMENTS: [usize; 16] = [
    16, 25, 32, 50, 64, 100, 141, 200, 283, 400, 566, 800, 1131, 1600, 2263, 3200,
];

/// The graded rods' atlas starts at this release angle, where `--tolerance` may choose
/// them ([`crate::methods::graded::SPIN_FREE_FROM`]).
pub const GRADED_FROM: f64 = crate::methods::graded::SPIN_FREE_FROM;

/// The simulated time over which the worst error is measured: the atlas serves runs no longer.
pub const WINDOW: f64 = 3.0;

/// The window of the graded rods' longer atlas (`graded-atlas-t5.csv`): runs from t = 3 to 5,
/// whose whips after t = 3 the shorter atlas never saw.
pub const LONGER_WINDOW: f64 = 5.0;

/// The graded rods' longer atlas starts at this release angle, from which `--tolerance` may
/// choose them past t = 3 ([`crate::methods::graded::SPIN_FREE_LONGER_FROM`]: below it their
/// end rods come out of a second whip, near t = 4.8, spinning).
pub const LONGER_FROM: f64 = crate::methods::graded::SPIN_FREE_LONGER_FROM;

/// An entry is trusted only where its reference's own error is at most this fraction of it.
pub const REFERENCE_MARGIN: f64 = 0.1;

/// Whether the atlas trusts a measured worst error against a reference whose own error is
/// `own`: a finite error at least 1/[`REFERENCE_MARGIN`] times it.
pub fn trusted(worst: f64, own: f64) -> bool {
    worst.is_finite() && own <= REFERENCE_MARGIN * worst
}

/// The measurements, as `scripts/release-atlas.sh` wrote them.
const CSV: &str = include_str!("../../../assets/release-atlas/atlas.csv");

/// The graded rods' measurements, as `scripts/release-atlas.sh graded` wrote them.
const GRADED_CSV: &str = include_str!("../../../assets/release-atlas/graded-atlas.csv");

/// The graded rods' measurements to [`LONGER_WINDOW`], as `scripts/release-atlas.sh graded
/// --until 5` wrote them.
const GRADED_LONGER_CSV: &str = include_str!("../../../assets/release-atlas/graded-atlas-t5.csv");

/// One angle's worst errors.
#[derive(Clone, Debug, PartialEq)]
struct Row {
    angle_deg: f64,
    /// A bound on the worst tip error at each of [`SEGMENTS`] (the measured error plus its
    /// reference's own), trusted from N = 16 up to the first that is not; `None` from there.
    bound: [Option<f64>; SEGMENTS.len()],
    /// Each finite measured worst error at [`SEGMENTS`] with its reference's own error, trusted
    /// or not: at the angle itself an entry serves any tolerance its reference could judge,
    /// and it says what the error is at least ([`Row::floor`]).
    measured: [Option<(f64, f64)>; SEGMENTS.len()],
}

impl Row {
    /// What the worst tip error at the `j`-th of [`SEGMENTS`] is at least (the measured error
    /// less its reference's own), trusted or not: an entry too coarse to bound the error still
    /// shows how far a held-out angle strays at least.
    fn floor(&self, j: usize) -> Option<f64> {
        let (worst, own) = self.measured[j]?;
        (worst > own).then_some(worst - own)
    }

    /// The bound at the `j`-th of [`SEGMENTS`] a law serving `tolerance` may read: a trusted
    /// entry's, or any entry's measured against a reference that could judge `tolerance` (the
    /// tolerance check's rule, [`serves`]): its error plus its reference's own bounds the
    /// error all the same. Trust (an error ten times its reference's own) is what a ratio
    /// needs, the margin; a bound needs only a reference fit to judge what it serves.
    fn bound_for(&self, j: usize, tolerance: f64) -> Option<f64> {
        self.bound[j].or_else(|| {
            let (worst, own) = self.measured[j]?;
            (own <= REFERENCE_MARGIN * tolerance).then_some(worst + own)
        })
    }
}

/// The atlas and held-out rows, and the margin the held-out rows measure.
#[derive(Clone, Debug, PartialEq)]
pub struct Atlas {
    rows: Vec<Row>,
    held_out: Vec<Row>,
    /// The largest ratio of a held-out angle's error to the larger of its neighbours' (≥ 1),
    /// over every N where both are trusted.
    pub margin: f64,
    /// At each of [`SEGMENTS`] where every angle (the atlas's and the held-out) was measured:
    /// the largest bound among them (measured error plus its reference's own), and the largest
    /// own error of their references (what tolerance the envelope can serve).
    envelope: [Option<Envelope>; SEGMENTS.len()],
    /// The largest ratio of one angle's bound to the envelope of all the others' (≥ 1), over
    /// every N where the envelope is: how far an angle may stray above every other angle's.
    pub envelope_margin: f64,
    /// The simulated time its worst errors were measured over: it serves runs no longer.
    pub window: f64,
}

/// The largest bound over every measured angle at one N.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Envelope {
    bound: f64,
    /// The largest own error of the references the bounds were measured against.
    own: f64,
}

/// Why the atlas file could not be read (a test reads the committed one).
#[derive(Debug, thiserror::Error)]
#[error("assets/release-atlas/atlas.csv, line {line}: {what}")]
pub struct AtlasError {
    line: usize,
    what: String,
}

impl Atlas {
    /// The committed atlas, read once; `None` if the file is absent or malformed (a test
    /// makes sure the committed one reads), in which case every release keeps the one law.
    pub fn committed() -> Option<&'static Atlas> {
        static ATLAS: OnceLock<Option<Atlas>> = OnceLock::new();
        ATLAS
            .get_or_init(|| Atlas::parse(CSV, WINDOW).ok())
            .as_ref()
    }

    /// The committed atlas of the graded rods (`assets/release-atlas/graded-atlas.csv`), read
    /// once; `None` if absent or malformed.
    pub fn committed_graded() -> Option<&'static Atlas> {
        static ATLAS: OnceLock<Option<Atlas>> = OnceLock::new();
        ATLAS
            .get_or_init(|| Atlas::parse(GRADED_CSV, WINDOW).ok())
            .as_ref()
    }

    /// The committed atlas of the graded rods to [`LONGER_WINDOW`]
    /// (`assets/release-atlas/graded-atlas-t5.csv`), read once; `None` if absent or malformed.
    /// Its margin is at least the shorter atlas's: its few held-out angles are a thin sample of
    /// how far an angle strays from its neighbours on these rods (to t = 3, 35° strayed 3.60
    /// times where 45° and 55° did not stray at all).
    pub fn committed_graded_longer() -> Option<&'static Atlas> {
        static ATLAS: OnceLock<Option<Atlas>> = OnceLock::new();
        ATLAS
            .get_or_init(|| {
                let mut atlas = Atlas::parse(GRADED_LONGER_CSV, LONGER_WINDOW).ok()?;
                let shorter = Self::committed_graded().map_or(1.0, |a| a.margin);
                atlas.margin = atlas.margin.max(shorter);
                Some(atlas)
            })
            .as_ref()
    }

    /// The committed atlas of the discretization `method` runs on (the chain's rods, or the
    /// graded rods) with the shortest window that covers a run of `duration`; `None` for
    /// another discretization (the report's finite differences) or a longer run.
    pub fn of(method: MethodKind, duration: f64) -> Option<&'static Atlas> {
        let discretization = method.descriptor().discretization;
        let atlases = if discretization == MethodKind::Chain.descriptor().discretization {
            [Self::committed(), None]
        } else if discretization == MethodKind::Graded.descriptor().discretization {
            [Self::committed_graded(), Self::committed_graded_longer()]
        } else {
            [None, None]
        };
        atlases
            .into_iter()
            .flatten()
            .find(|atlas| duration <= atlas.window)
    }

    /// Reads the CSV `scripts/release-atlas.sh` writes: a header, then
    /// `set,angle_deg,segments,worst,reference_segments,reference_own_error` lines, `set`
    /// being `atlas` or `held-out`, each the worst error over `window`.
    pub fn parse(text: &str, window: f64) -> Result<Atlas, AtlasError> {
        let mut rows: Vec<Row> = Vec::new();
        let mut held_out: Vec<Row> = Vec::new();
        for (i, line) in text.lines().enumerate().skip(1) {
            let bad = |what: &str| AtlasError {
                line: i + 1,
                what: what.to_owned(),
            };
            let fields: Vec<&str> = line.split(',').collect();
            let [set, angle, segments, worst, _, own] = fields.as_slice() else {
                return Err(bad("six fields expected"));
            };
            let number = |s: &str| s.trim().parse::<f64>().map_err(|_| bad("not a number"));
            let (angle_deg, worst, own) = (number(angle)?, number(worst)?, number(own)?);
            let segments: usize = segments.trim().parse().map_err(|_| bad("not a count"))?;
            let j = SEGMENTS
                .iter()
                .position(|&n| n == segments)
                .ok_or_else(|| bad("a segment count the atlas does not measure"))?;
            let table = match *set {
                "atlas" => &mut rows,
                "held-out" => &mut held_out,
                _ => return Err(bad("the set is neither atlas nor held-out")),
            };
            if table.last().is_none_or(|r| r.angle_deg != angle_deg) {
                table.push(Row {
                    angle_deg,
                    bound: [None; SEGMENTS.len()],
                    measured: [None; SEGMENTS.len()],
                });
            }
            if let Some(row) = table.last_mut() {
                row.bound[j] = trusted(worst, own).then_some(worst + own);
                row.measured[j] = (worst.is_finite() && own.is_finite()).then_some((worst, own));
            }
        }
        for row in &mut rows {
            // Trusted from N = 16 up to the first that is not.
            if let Some(first_gap) = row.bound.iter().position(Option::is_none) {
                row.bound[first_gap..].fill(None);
            }
        }
        rows.sort_by(|a, b| a.angle_deg.total_cmp(&b.angle_deg));
        if rows.len() < 2 {
            return Err(AtlasError {
                line: 1,
                what: "fewer than two atlas angles".to_owned(),
            });
        }
        let mut atlas = Atlas {
            rows,
            held_out,
            margin: 1.0,
            envelope: [None; SEGMENTS.len()],
            envelope_margin: 1.0,
            window,
        };
        (atlas.envelope, atlas.envelope_margin) = atlas.envelope_and_margin();
        // At each N where the neighbours are trusted: the held-out angle's bound where it is
        // trusted, else what its error is at least.
        atlas.margin = atlas
            .held_out
            .iter()
            .filter_map(|h| Some((h, atlas.neighbours(h.angle_deg)?)))
            .flat_map(|(h, neighbours)| {
                (0..SEGMENTS.len())
                    .filter_map(move |j| Some(h.bound[j].or(h.floor(j))? / neighbours[j]?))
            })
            .fold(1.0, f64::max);
        Ok(atlas)
    }

    /// The envelope of every measured angle's bounds at each N where all were measured, and
    /// its leave-one-out margin: at each such N, each angle's bound over the largest of all
    /// the others' (conservative: the left-out angle's error is taken at its bound).
    fn envelope_and_margin(&self) -> ([Option<Envelope>; SEGMENTS.len()], f64) {
        let every: Vec<&Row> = self.rows.iter().chain(&self.held_out).collect();
        let mut margin = 1f64;
        let envelope = std::array::from_fn(|j| {
            let entries: Vec<(f64, f64)> =
                every.iter().map(|r| r.measured[j]).collect::<Option<_>>()?;
            let bounds: Vec<f64> = entries.iter().map(|(worst, own)| worst + own).collect();
            for (i, bound) in bounds.iter().enumerate() {
                let others = bounds
                    .iter()
                    .enumerate()
                    .filter(|&(k, _)| k != i)
                    .map(|(_, b)| *b)
                    .fold(0.0, f64::max);
                if others > 0.0 {
                    margin = margin.max(bound / others);
                }
            }
            Some(Envelope {
                bound: bounds.iter().copied().fold(0.0, f64::max),
                own: entries.iter().map(|(_, own)| *own).fold(0.0, f64::max),
            })
        });
        (envelope, margin)
    }

    /// The envelope times its margin, as (N, bound) at each N where every angle was measured
    /// and it could serve a tolerance that large (its references' own errors at most
    /// [`REFERENCE_MARGIN`] times it): what the atlas bounds an angle between its own by (the
    /// chart draws it).
    pub fn envelope(&self) -> impl Iterator<Item = (usize, f64)> + '_ {
        SEGMENTS.iter().zip(&self.envelope).filter_map(|(&n, e)| {
            let e = e.as_ref()?;
            let bound = e.bound * self.envelope_margin;
            serves(bound, e.own, bound).then_some((n, bound))
        })
    }

    /// Each atlas angle's trusted bounds, as (N, worst error) from N = 16 up: what the chart
    /// draws.
    pub fn rows(&self) -> impl Iterator<Item = (f64, Vec<(usize, f64)>)> + '_ {
        self.rows_by(|row, j| row.bound[j])
    }

    /// Each atlas angle's bounds from N = 16 up that a law serving `tolerance` reads (trusted,
    /// or measured against a reference that could judge `tolerance`), as (N, bound): the chart
    /// draws past the trusted ones ([`Atlas::rows`]) what such references still bound.
    pub fn rows_serving(
        &self,
        tolerance: f64,
    ) -> impl Iterator<Item = (f64, Vec<(usize, f64)>)> + '_ {
        self.rows_by(move |row, j| row.bound_for(j, tolerance))
    }

    /// Each atlas angle's `bound` at [`SEGMENTS`] from N = 16 up to the first it has none, as
    /// (N, bound).
    fn rows_by(
        &self,
        bound: impl Fn(&Row, usize) -> Option<f64> + Copy + 'static,
    ) -> impl Iterator<Item = (f64, Vec<(usize, f64)>)> + '_ {
        self.rows.iter().map(move |row| {
            let bounds = (0..SEGMENTS.len())
                .map_while(|j| Some((SEGMENTS[j], bound(row, j)?)))
                .collect();
            (row.angle_deg, bounds)
        })
    }

    /// The larger of the two atlas rows' bounds around `angle_deg` at each of [`SEGMENTS`] (the
    /// one row at an atlas angle), where both are trusted; `None` outside the atlas's angles.
    pub fn neighbours(&self, angle_deg: f64) -> Option<[Option<f64>; SEGMENTS.len()]> {
        self.neighbours_by(angle_deg, |row, j| row.bound[j])
    }

    /// As [`Atlas::neighbours`], with every bound a law serving `tolerance` may read
    /// ([`Row::bound_for`]).
    fn neighbours_serving(
        &self,
        angle_deg: f64,
        tolerance: f64,
    ) -> Option<[Option<f64>; SEGMENTS.len()]> {
        self.neighbours_by(angle_deg, |row, j| row.bound_for(j, tolerance))
    }

    /// The larger of `bound` of the two atlas rows around `angle_deg` at each of [`SEGMENTS`],
    /// where both have one; `None` outside the atlas's angles.
    fn neighbours_by(
        &self,
        angle_deg: f64,
        bound: impl Fn(&Row, usize) -> Option<f64>,
    ) -> Option<[Option<f64>; SEGMENTS.len()]> {
        let i = self.rows.iter().position(|r| r.angle_deg >= angle_deg)?;
        let high = &self.rows[i];
        let low = match high.angle_deg == angle_deg {
            true => high,
            false => self.rows.get(i.checked_sub(1)?)?,
        };
        Some(std::array::from_fn(|j| {
            match (bound(low, j), bound(high, j)) {
                (Some(a), Some(b)) => Some(a.max(b)),
                _ => None,
            }
        }))
    }

    /// The rods' error model from `scene` to `duration` for `tolerance`: of the three below, the
    /// one that asks fewer segments; `None` for a mode, a run longer than its window, or a
    /// tolerance neither reaches.
    /// - At an angle the atlas measured, that angle's own row: the fewest N it measured whose
    ///   bound holds `tolerance` (`Atlas::measured`). No margin: nothing is interpolated.
    /// - Everywhere, the interpolated law: first order, its constant the largest bound × N of
    ///   the angle's neighbours (wherever their references could judge `tolerance`, times
    ///   [`Atlas::margin`]) at the fewest N of the atlas from which it holds `tolerance`.
    /// - Between the atlas's angles, the envelope: the fewest N whose largest bound over every
    ///   angle measured, times [`Atlas::envelope_margin`], holds `tolerance`
    ///   (`Atlas::enveloped`).
    pub fn model(&self, scene: &Scene, duration: f64, tolerance: f64) -> Option<ErrorModel> {
        let Scene::Release { angle_deg } = *scene else {
            return None;
        };
        if duration.is_nan() || duration > self.window || tolerance.is_nan() || tolerance <= 0.0 {
            return None;
        }
        let measured = self.measured(angle_deg, tolerance);
        let interpolated = self.interpolated(angle_deg, tolerance);
        let enveloped = self.enveloped(angle_deg, tolerance);
        [measured, interpolated, enveloped]
            .into_iter()
            .flatten()
            .min_by_key(|model| model.segments_for(tolerance))
    }

    /// At an angle of the atlas's own or held-out rows, the fewest of [`SEGMENTS`] whose bound
    /// (the measured worst error plus its reference's own) is within `tolerance`, measured
    /// against a reference that could judge `tolerance` (its own error at most
    /// [`REFERENCE_MARGIN`] × `tolerance`, the tolerance check's rule), as a law that asks
    /// exactly that N ([`asking`]); `None` at another angle, or where no such N holds it. An
    /// entry need not be trusted for the margin (its error ten times its reference's own): a
    /// bound is a bound, and nothing is interpolated from it.
    fn measured(&self, angle_deg: f64, tolerance: f64) -> Option<ErrorModel> {
        let row = self
            .rows
            .iter()
            .chain(&self.held_out)
            .find(|r| r.angle_deg == angle_deg)?;
        let j = row.measured.iter().position(|entry| {
            entry.is_some_and(|(worst, own)| serves(worst + own, own, tolerance))
        })?;
        Some(asking(SEGMENTS[j], tolerance))
    }

    /// Between the atlas's first and last angles, the fewest of [`SEGMENTS`] whose envelope
    /// (the largest bound of every angle measured there) times [`Atlas::envelope_margin`] is
    /// within `tolerance`, where every reference could judge `tolerance` (as
    /// [`Atlas::measured`]), as a law that asks exactly that N ([`asking`]); `None` outside
    /// those angles or where no such N holds it.
    fn enveloped(&self, angle_deg: f64, tolerance: f64) -> Option<ErrorModel> {
        let (first, last) = (self.rows.first()?, self.rows.last()?);
        if !(first.angle_deg..=last.angle_deg).contains(&angle_deg) {
            return None;
        }
        let j = self.envelope.iter().position(|envelope| {
            envelope.is_some_and(|e| serves(e.bound * self.envelope_margin, e.own, tolerance))
        })?;
        Some(asking(SEGMENTS[j], tolerance))
    }

    /// The first-order law from the neighbours' rows times the margin (see [`Atlas::model`]),
    /// the one asking the fewest segments of those read to each N from the neighbours' last
    /// trusted one up to their last bounded for `tolerance` ([`Row::bound_for`]). A bound whose
    /// reference merely could judge `tolerance` carries that reference's own error, which
    /// grows its constant with N: it is read only as far as a choice needs it, and the law
    /// from the trusted bounds alone is always among those weighed.
    fn interpolated(&self, angle_deg: f64, tolerance: f64) -> Option<ErrorModel> {
        let leading =
            |bound: [Option<f64>; SEGMENTS.len()]| bound.iter().take_while(|b| b.is_some()).count();
        let bound = self.neighbours_serving(angle_deg, tolerance)?;
        let trusted = self.neighbours(angle_deg).map_or(0, leading);
        (trusted.max(1)..=leading(bound))
            .filter_map(|end| self.law_to(&bound[..end], tolerance))
            .min_by_key(|&(needed, _)| needed)
            .map(|(_, law)| law)
    }

    /// The first-order law from `bound` (the neighbours' bounds at [`SEGMENTS`] from N = 16 on,
    /// every one given) times the margin, with the segments it asks for `tolerance`: a bound
    /// at every N from where it starts to the last of `bound`; `None` if it would ask more.
    fn law_to(&self, bound: &[Option<f64>], tolerance: f64) -> Option<(usize, ErrorModel)> {
        let last = *SEGMENTS.get(bound.len().checked_sub(1)?)?;
        // Each N with the largest constant (bound × N) there and above: a bound at every N
        // from it up.
        let mut tail = 0f64;
        let constants: Vec<(usize, f64)> = (0..bound.len())
            .rev()
            .map(|j| {
                tail = tail.max(bound[j].unwrap_or(f64::INFINITY) * SEGMENTS[j] as f64);
                (SEGMENTS[j], tail)
            })
            .collect();
        // The fewest segments each constant asks for, never fewer than where it starts to
        // bound, and none past the last N read.
        let (needed, from, constant) = constants
            .into_iter()
            .map(|(n, c)| {
                let needed = (self.margin * c / tolerance - 1e-9).ceil() as usize;
                (needed.max(n), n, c)
            })
            .filter(|&(needed, _, _)| needed <= last)
            .min_by_key(|&(needed, _, _)| needed)?;
        // Where the constant itself would ask for fewer than `from`, the law is raised to ask
        // for `from`: its bound there is then `tolerance`, above what the atlas measured.
        let at_least = match needed == from {
            true => tolerance * (from as f64 - 0.5) / self.margin,
            false => 0.0,
        };
        let law = ErrorModel {
            constant: constant.max(at_least),
            order: 1.0,
            safety: self.margin,
        };
        Some((needed, law))
    }
}

/// Whether `bound` holds `tolerance`, measured against references whose own error, at most
/// `own`, could judge it (at most [`REFERENCE_MARGIN`] × `tolerance`: the tolerance check's
/// rule).
fn serves(bound: f64, own: f64, tolerance: f64) -> bool {
    own <= REFERENCE_MARGIN * tolerance && bound <= tolerance
}

/// A first-order law that asks exactly `segments` for `tolerance`: its bound there is just
/// under `tolerance`, and at least what was measured.
fn asking(segments: usize, tolerance: f64) -> ErrorModel {
    ErrorModel {
        constant: tolerance * (segments as f64 - 0.5),
        order: 1.0,
        safety: 1.0,
    }
}

#[cfg(test)]
mod tests;
