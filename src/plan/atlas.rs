//! The release atlas: the committed error model of a release, per release angle.
//!
//! A method's one error law ([`Descriptor::error_model`](crate::methods::Descriptor::error_model)) is
//! the worst of six scenes up to large N: the horizontal release's whip, whose error constant
//! stays near 0.45/N. From most other angles the rods' worst tip error to t = 3 is far from
//! one law: its constant rises and falls with N by up to a factor of 2 (from 30° it falls from
//! 0.42/N at N = 64 to 0.21/N at N = 400; from 80° it grows from 0.11/N at N = 16 to 0.20/N
//! at N = 200), and the pilots, at N ≤ 64, see only the start of it. The atlas is that error
//! measured: the chain at its tolerance step from each release angle 0°, 10°, …, 90° at
//! N = 16 … 566, against the chain extrapolated from N = 800, 1600 and 3200
//! (`scripts/release-atlas.sh`, which writes `assets/release-atlas/atlas.csv`, read here at
//! build time).
//!
//! At an angle the atlas measured, a tolerance may be met by an N it measured there: the
//! fewest whose bound (the measured error plus its reference's own) holds it, with no margin,
//! since nothing is interpolated. Otherwise, and wherever it asks fewer segments, for an angle
//! between two of the atlas's the larger of their two errors at each N is taken, times a
//! margin measured at the held-out angles 5°, 15°, …, 85°: the largest ratio of a held-out
//! angle's error to that of its two neighbours (where its reference is too coarse to bound its
//! error, what the error is at least: the measured error less the reference's own). Between
//! the atlas's N, the error is taken as first order from the largest constant (error × N) at
//! that N and above. The atlas serves only what it measured: the rods, a release, runs to
//! t ≤ 3, N ≤ 566 (the graded rods' to 1131), and errors at least ten times its references'
//! own; elsewhere the method's one law stands.

use crate::methods::MethodKind;
use crate::methods::error_model::ErrorModel;
use crate::model::Scene;
use std::sync::OnceLock;

/// The release angles the atlas measures, in degrees below the horizontal.
pub const ATLAS_ANGLES: [f64; 10] = [0.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0, 90.0];

/// The angles measured only to find the margin for angles between the atlas's.
pub const HELD_OUT_ANGLES: [f64; 9] = [5.0, 15.0, 25.0, 35.0, 45.0, 55.0, 65.0, 75.0, 85.0];

/// The segment counts measured at each angle (√2 apart from 50 up). The chain's atlas was
/// measured to 566, the graded rods' to 1131.
pub const SEGMENTS: [usize; 13] = [16, 25, 32, 50, 64, 100, 141, 200, 283, 400, 566, 800, 1131];

/// The graded rods' atlas starts at this release angle, where `--tolerance` may choose
/// them ([`crate::methods::graded::SPIN_FREE_FROM`]).
pub const GRADED_FROM: f64 = crate::methods::graded::SPIN_FREE_FROM;

/// The simulated time over which the worst error is measured: the atlas serves runs no longer.
pub const WINDOW: f64 = 3.0;

/// An entry is trusted only where its reference's own error is at most this fraction of it.
pub const REFERENCE_MARGIN: f64 = 0.1;

/// Whether the atlas trusts a measured worst error against a reference whose own error is
/// `own`: a finite error at least 1/[`REFERENCE_MARGIN`] times it.
pub fn trusted(worst: f64, own: f64) -> bool {
    worst.is_finite() && own <= REFERENCE_MARGIN * worst
}

/// The measurements, as `scripts/release-atlas.sh` wrote them.
const CSV: &str = include_str!("../../assets/release-atlas/atlas.csv");

/// The graded rods' measurements, as `scripts/release-atlas.sh graded` wrote them.
const GRADED_CSV: &str = include_str!("../../assets/release-atlas/graded-atlas.csv");

/// One angle's worst errors.
#[derive(Clone, Debug, PartialEq)]
struct Row {
    angle_deg: f64,
    /// A bound on the worst tip error at each of [`SEGMENTS`] (the measured error plus its
    /// reference's own), trusted from N = 16 up to the first that is not; `None` from there.
    bound: [Option<f64>; SEGMENTS.len()],
    /// What the worst tip error at each of [`SEGMENTS`] is at least (the measured error less
    /// its reference's own), trusted or not: an entry too coarse to bound the error still
    /// shows how far a held-out angle strays at least.
    floor: [Option<f64>; SEGMENTS.len()],
}

/// The atlas and held-out rows, and the margin the held-out rows measure.
#[derive(Clone, Debug, PartialEq)]
pub struct Atlas {
    rows: Vec<Row>,
    held_out: Vec<Row>,
    /// The largest ratio of a held-out angle's error to the larger of its neighbours' (≥ 1),
    /// over every N where both are trusted.
    pub margin: f64,
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
        ATLAS.get_or_init(|| Atlas::parse(CSV).ok()).as_ref()
    }

    /// The committed atlas of the graded rods (`assets/release-atlas/graded-atlas.csv`), read
    /// once; `None` if absent or malformed.
    pub fn committed_graded() -> Option<&'static Atlas> {
        static ATLAS: OnceLock<Option<Atlas>> = OnceLock::new();
        ATLAS.get_or_init(|| Atlas::parse(GRADED_CSV).ok()).as_ref()
    }

    /// The committed atlas of the discretization `method` runs on: the chain's rods, or the
    /// graded rods; `None` for another (the report's finite differences).
    pub fn of(method: MethodKind) -> Option<&'static Atlas> {
        let discretization = method.descriptor().discretization;
        if discretization == MethodKind::Chain.descriptor().discretization {
            Self::committed()
        } else if discretization == MethodKind::Graded.descriptor().discretization {
            Self::committed_graded()
        } else {
            None
        }
    }

    /// Reads the CSV `scripts/release-atlas.sh` writes: a header, then
    /// `set,angle_deg,segments,worst,reference_segments,reference_own_error` lines, `set`
    /// being `atlas` or `held-out`.
    pub fn parse(text: &str) -> Result<Atlas, AtlasError> {
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
                    floor: [None; SEGMENTS.len()],
                });
            }
            if let Some(row) = table.last_mut() {
                row.bound[j] = trusted(worst, own).then_some(worst + own);
                row.floor[j] = (worst.is_finite() && worst > own).then_some(worst - own);
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
        };
        // At each N where the neighbours are trusted: the held-out angle's bound where it is
        // trusted, else what its error is at least.
        atlas.margin = atlas
            .held_out
            .iter()
            .filter_map(|h| Some((h, atlas.neighbours(h.angle_deg)?)))
            .flat_map(|(h, neighbours)| {
                (0..SEGMENTS.len())
                    .filter_map(move |j| Some(h.bound[j].or(h.floor[j])? / neighbours[j]?))
            })
            .fold(1.0, f64::max);
        Ok(atlas)
    }

    /// Each atlas angle's trusted bounds, as (N, worst error) from N = 16 up: what the chart
    /// draws.
    pub fn rows(&self) -> impl Iterator<Item = (f64, Vec<(usize, f64)>)> + '_ {
        self.rows.iter().map(|r| {
            let trusted = SEGMENTS
                .iter()
                .zip(r.bound)
                .map_while(|(&n, b)| Some((n, b?)))
                .collect();
            (r.angle_deg, trusted)
        })
    }

    /// The larger of the two atlas rows' bounds around `angle_deg` at each of [`SEGMENTS`] (the
    /// one row at an atlas angle), where both are trusted; `None` outside the atlas's angles.
    pub fn neighbours(&self, angle_deg: f64) -> Option<[Option<f64>; SEGMENTS.len()]> {
        let i = self.rows.iter().position(|r| r.angle_deg >= angle_deg)?;
        let high = &self.rows[i];
        let low = match high.angle_deg == angle_deg {
            true => high,
            false => self.rows.get(i.checked_sub(1)?)?,
        };
        Some(std::array::from_fn(|j| {
            match (low.bound[j], high.bound[j]) {
                (Some(a), Some(b)) => Some(a.max(b)),
                _ => None,
            }
        }))
    }

    /// The rods' error model from `scene` to `duration` for `tolerance`: of the two below, the
    /// one that asks fewer segments; `None` for a mode, a run longer than [`WINDOW`], or a
    /// tolerance neither reaches.
    /// - At an angle the atlas measured, that angle's own row: the fewest N it measured whose
    ///   bound holds `tolerance` (`Atlas::measured`). No margin: nothing is interpolated.
    /// - Everywhere, the interpolated law: first order, its constant the largest error × N of
    ///   the angle's neighbours (times [`Atlas::margin`]) at the fewest N of the atlas from
    ///   which it holds `tolerance`.
    pub fn model(&self, scene: &Scene, duration: f64, tolerance: f64) -> Option<ErrorModel> {
        let Scene::Release { angle_deg } = *scene else {
            return None;
        };
        if duration.is_nan() || duration > WINDOW || tolerance.is_nan() || tolerance <= 0.0 {
            return None;
        }
        let measured = self.measured(angle_deg, tolerance);
        let interpolated = self.interpolated(angle_deg, tolerance);
        [measured, interpolated]
            .into_iter()
            .flatten()
            .min_by_key(|model| model.segments_for(tolerance))
    }

    /// At an angle of the atlas's own rows, the fewest of [`SEGMENTS`] whose trusted bound (the
    /// measured worst error plus its reference's own) is within `tolerance`, as a law that asks
    /// exactly that N for `tolerance` (its bound there is just under `tolerance`, and at least
    /// what was measured); `None` at another angle, or where no trusted N holds it.
    fn measured(&self, angle_deg: f64, tolerance: f64) -> Option<ErrorModel> {
        let row = self.rows.iter().find(|r| r.angle_deg == angle_deg)?;
        let j = row
            .bound
            .iter()
            .map_while(|b| *b)
            .position(|bound| bound <= tolerance)?;
        Some(ErrorModel {
            constant: tolerance * (SEGMENTS[j] as f64 - 0.5),
            order: 1.0,
            safety: 1.0,
        })
    }

    /// The first-order law from the neighbours' rows times the margin (see [`Atlas::model`]).
    fn interpolated(&self, angle_deg: f64, tolerance: f64) -> Option<ErrorModel> {
        let bound = self.neighbours(angle_deg)?;
        let trusted = bound.iter().take_while(|b| b.is_some()).count();
        let last = *SEGMENTS.get(trusted.checked_sub(1)?)?;
        // Each trusted N with the largest constant (error × N) there and above: a bound at
        // every N from it up.
        let mut tail = 0f64;
        let constants: Vec<(usize, f64)> = (0..trusted)
            .rev()
            .map(|j| {
                tail = tail.max(bound[j].unwrap_or(f64::INFINITY) * SEGMENTS[j] as f64);
                (SEGMENTS[j], tail)
            })
            .collect();
        // The fewest segments each constant asks for, never fewer than where it starts to
        // bound, and none past the atlas's trusted N.
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
        Some(ErrorModel {
            constant: constant.max(at_least),
            order: 1.0,
            safety: self.margin,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn csv(rows: &[(&str, f64, [f64; SEGMENTS.len()])]) -> String {
        let mut text =
            "set,angle_deg,segments,worst,reference_segments,reference_own_error\n".to_owned();
        for (set, angle, errors) in rows {
            for (n, e) in SEGMENTS.iter().zip(errors) {
                text += &format!("{set},{angle},{n},{e:e},1600,0\n");
            }
        }
        text
    }

    /// Errors c/N at every N.
    fn law(c: f64) -> [f64; SEGMENTS.len()] {
        SEGMENTS.map(|n| c / n as f64)
    }

    /// The atlas of errors 0.4/N at 0° and 0.2/N at 10°, and `held_out`/N at 5°: its margin
    /// `held_out` / 0.4.
    fn two_angles_and_5_degrees_held_out(held_out: f64) -> Atlas {
        let text = csv(&[
            ("atlas", 0.0, law(0.4)),
            ("atlas", 10.0, law(0.2)),
            ("held-out", 5.0, law(held_out)),
        ]);
        Atlas::parse(&text).expect("the atlas reads")
    }

    #[test]
    fn the_committed_atlas_reads_and_its_margin_is_measured() {
        let atlas = Atlas::parse(CSV).expect("the committed atlas reads");
        assert_eq!(atlas.rows.len(), ATLAS_ANGLES.len());
        assert_eq!(atlas.held_out.len(), HELD_OUT_ANGLES.len());
        assert!(
            atlas.margin >= 1.0 && atlas.margin < 2.0,
            "{}",
            atlas.margin
        );
    }

    #[test]
    fn the_committed_graded_atlas_reads_from_20_degrees_and_the_law_bounds_it() {
        let atlas = Atlas::parse(GRADED_CSV).expect("the committed graded atlas reads");
        assert!(atlas.rows.iter().all(|r| r.angle_deg >= GRADED_FROM));
        assert!(atlas.margin >= 1.0, "{}", atlas.margin);
        // With its margin it still reaches 1e-4 from 20° to 40° (where the law asks N = 4 901),
        // within the N it measured.
        for angle_deg in [20.0, 30.0, 40.0] {
            let model = atlas
                .model(&Scene::Release { angle_deg }, 3.0, 1e-4)
                .unwrap_or_else(|| panic!("{angle_deg}°: no model at 1e-4"));
            assert!(model.segments_for(1e-4) <= SEGMENTS[SEGMENTS.len() - 1]);
        }
        // The graded rods borrow the chain's one law: it bounds every trusted entry.
        let law = MethodKind::Graded.descriptor().error_model;
        for (angle, points) in atlas.rows() {
            for (n, error) in points {
                assert!(error <= law.bound(n), "{angle}° at N = {n}: {error:e}");
            }
        }
    }

    /// The held-out rows are measurements at angles the atlas's rows do not include: wherever
    /// a held-out angle's choice claims to hold, its own row must not show an error past the
    /// tolerance (at least: the measured error less its reference's own).
    #[test]
    fn every_choice_at_a_held_out_angle_holds_where_that_angle_was_measured() {
        for (name, text) in [("chain", CSV), ("graded", GRADED_CSV)] {
            let atlas = Atlas::parse(text).expect("the committed atlas reads");
            for held in &atlas.held_out {
                let scene = Scene::Release {
                    angle_deg: held.angle_deg,
                };
                for tolerance in [1e-2, 3e-3, 1e-3, 3e-4, 1e-4] {
                    let Some(model) = atlas.model(&scene, WINDOW, tolerance) else {
                        continue;
                    };
                    let chosen = model.segments_for(tolerance);
                    for (n, floor) in SEGMENTS.iter().zip(held.floor) {
                        let at_least = floor.unwrap_or(0.0);
                        assert!(
                            *n < chosen || at_least <= tolerance,
                            "{name}, {}° at {tolerance:e}: N = {chosen} chosen, but at N = {n} \
                             the error is at least {at_least:.2e}",
                            held.angle_deg
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn an_angle_between_two_takes_the_larger_error_and_the_held_out_margin() {
        let atlas = two_angles_and_5_degrees_held_out(0.5);
        assert!((atlas.margin - 1.25).abs() < 1e-12);
        let model = atlas
            .model(&Scene::Release { angle_deg: 7.0 }, 3.0, 1e-3)
            .unwrap();
        // 0.4 × 1.25 / 1e-3 = 500 segments.
        assert_eq!(model.segments_for(1e-3), 500);
        // Past the atlas's N, in a mode, or past its window: no model.
        assert!(
            atlas
                .model(&Scene::Release { angle_deg: 7.0 }, 3.0, 1e-4)
                .is_none()
        );
        assert!(
            atlas
                .model(&Scene::Release { angle_deg: 7.0 }, 3.5, 1e-3)
                .is_none()
        );
        let mode = Scene::Mode {
            number: 1,
            amplitude: 0.05,
        };
        assert!(atlas.model(&mode, 3.0, 1e-3).is_none());
    }

    #[test]
    fn at_an_atlas_angle_the_fewest_measured_n_whose_bound_holds_is_chosen_without_the_margin() {
        let atlas = two_angles_and_5_degrees_held_out(0.8);
        assert!((atlas.margin - 2.0).abs() < 1e-12);
        let at = |angle_deg, eps| {
            let model = atlas.model(&Scene::Release { angle_deg }, 3.0, eps)?;
            Some(model.segments_for(eps))
        };
        // At 10°, 0.2/N is within 1e-3 from N = 200, which the atlas measured; the law times
        // the margin would ask for 400.
        assert_eq!(at(10.0, 1e-3), Some(200));
        // Within 1.5e-3 from N = 133.3: the next measured, 141 (the law times the margin: 267).
        assert_eq!(at(10.0, 1.5e-3), Some(141));
        // Where the law times the margin asks fewer than the next measured N, the law: with no
        // held-out angle (a margin of 1), 1e-2 from 0.2/N asks for 20, where the next measured
        // N is 25.
        let no_margin =
            Atlas::parse(&csv(&[("atlas", 0.0, law(0.4)), ("atlas", 10.0, law(0.2))])).unwrap();
        let model = no_margin.model(&Scene::Release { angle_deg: 10.0 }, 3.0, 1e-2);
        assert_eq!(model.map(|m| m.segments_for(1e-2)), Some(20));
        // Between two atlas angles, the margin: 0.4 × 2 / 1e-3.
        assert_eq!(at(7.0, 1e-3), Some(800));
        // At 0°, 0.4/N is within 1e-4 only from N = 4 000, past what was measured: no model.
        assert_eq!(at(0.0, 1e-4), None);
    }

    #[test]
    fn an_untrusted_held_out_error_still_raises_the_margin_by_what_it_is_at_least() {
        let mut text = csv(&[("atlas", 0.0, law(0.4)), ("atlas", 10.0, law(0.2))]);
        // The 5° row errs by 0.4/N, but at N = 566 by 0.9/N against a reference whose own
        // error is 2e-4 (untrusted): the error there is at least (0.9/566 − 2e-4), 1.97 times
        // its neighbours'.
        for (n, e) in SEGMENTS.iter().zip(law(0.4)) {
            let (e, own) = match *n == 566 {
                true => (0.9 / 566.0, 2e-4),
                false => (e, 0.0),
            };
            text += &format!("held-out,5,{n},{e:e},1600,{own:e}\n");
        }
        let atlas = Atlas::parse(&text).unwrap();
        let expected = (0.9 / 566.0 - 2e-4) / (0.4 / 566.0);
        assert!((atlas.margin - expected).abs() < 1e-9, "{}", atlas.margin);
        // An entry that errs by less than its reference's own says nothing.
        let quiet = text.replace(
            &format!("{:e},1600,{:e}", 0.9 / 566.0, 2e-4),
            "1e-4,1600,2e-4",
        );
        assert_eq!(Atlas::parse(&quiet).unwrap().margin, 1.0);
    }

    #[test]
    fn a_constant_that_falls_with_n_is_used_only_from_where_it_falls() {
        // 0.4/N up to N = 100, then 0.2/N: 1e-3 needs N = 200 from the smaller constant
        // (0.2 / 1e-3), though 0.2 / 1.2e-3 alone would ask for 167 < 200 … from N = 141 up.
        let mut errors = law(0.4);
        for (e, n) in errors.iter_mut().zip(SEGMENTS) {
            if n >= 141 {
                *e = 0.2 / n as f64;
            }
        }
        let atlas = Atlas::parse(&csv(&[("atlas", 0.0, errors), ("atlas", 10.0, errors)])).unwrap();
        let at = |eps| {
            atlas
                .model(&Scene::Release { angle_deg: 0.0 }, 3.0, eps)
                .unwrap()
                .segments_for(eps)
        };
        assert_eq!(at(1e-3), 200);
        // 1.6e-3 would need 125 by the smaller constant: it bounds only from 141 up.
        assert_eq!(at(1.6e-3), 141);
        // 1e-2: 40 by the larger constant, which bounds every N.
        assert_eq!(at(1e-2), 40);
    }

    #[test]
    fn an_entry_whose_reference_is_too_coarse_ends_the_row() {
        let mut text = csv(&[("atlas", 10.0, law(0.2))]);
        // The 0° row: its reference's own error 1e-3, above a tenth of every error past N = 50.
        for (n, e) in SEGMENTS.iter().zip(law(0.5)) {
            text += &format!("atlas,0,{n},{e:e},1600,1e-3\n");
        }
        let atlas = Atlas::parse(&text).unwrap();
        let release = Scene::Release { angle_deg: 0.0 };
        assert_eq!(
            atlas.model(&release, 3.0, 2e-2).unwrap().segments_for(2e-2),
            28
        );
        assert!(atlas.model(&release, 3.0, 5e-3).is_none());
    }
}
