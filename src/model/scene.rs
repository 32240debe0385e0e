//! Scenes: the initial states a run starts from, each a small function of the segment count.

use super::bessel;
use super::fold;
use super::theory::{Comparison, Reading};
use crate::error::ConfigError;
use std::f64::consts::{FRAC_PI_2, PI};

/// An initial state of the string: angles of its segments, at rest.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum Scene {
    /// Straight and at rest at `angle_deg` degrees below the horizontal (the report's case).
    Release { angle_deg: f64 },
    /// Hanging straight down at rest, displaced by a small amplitude in the shape of the
    /// `number`-th small-oscillation mode (D. Bernoulli). `amplitude` is the tip's sideways
    /// displacement in string lengths.
    Mode { number: u32, amplitude: f64 },
    /// Folded in a U and at rest: both ends at the support's height, `gap` apart, the bottom
    /// a half circle of diameter `gap`; the end away from the support is let go (Calkin &
    /// March's falling chain, [`fold`]).
    Fold { gap: f64 },
}

/// The largest gap a fold can have: at 2/π the half circle takes the whole string.
pub const FOLD_GAP_MAX: f64 = 2.0 / PI;

/// The fewest rods across a fold's gap (d/h) for its bend to be drawn well enough to follow
/// Calkin & March's prediction: at two, `midpoint`'s free end was within 0.8 % of its
/// speed to x = 0.75 at N = 50 … 400; below one, up to 11 % off (`examples/fold_bend.rs`,
/// `assets/fold/bend.csv`).
pub const FOLD_RODS_ACROSS_GAP: f64 = 2.0;

impl Scene {
    /// Short name used on the command line and in summaries.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Release { .. } => "release",
            Self::Mode { .. } => "mode",
            Self::Fold { .. } => "fold",
        }
    }

    /// Checks the scene's own parameters (the method checks what it can start from).
    pub fn validate(&self) -> Result<(), ConfigError> {
        match *self {
            Self::Release { angle_deg } => {
                if !(0.0..=90.0).contains(&angle_deg) {
                    return Err(ConfigError::Angle(angle_deg));
                }
            }
            Self::Mode { number, amplitude } => {
                if !(1..=4).contains(&number) {
                    return Err(ConfigError::ModeNumber(number));
                }
                if !amplitude.is_finite() || amplitude.abs() > 0.2 {
                    return Err(ConfigError::Amplitude(amplitude));
                }
            }
            Self::Fold { gap } => {
                if !(gap > 0.0 && gap < FOLD_GAP_MAX) {
                    return Err(ConfigError::FoldGap(gap));
                }
            }
        }
        Ok(())
    }

    /// The initial angle of the string at the support, in radians below the horizontal.
    pub fn support_angle(&self) -> f64 {
        match *self {
            Self::Release { angle_deg } => angle_deg.to_radians(),
            Self::Mode { .. } | Self::Fold { .. } => FRAC_PI_2,
        }
    }

    /// The small-oscillation period of the `mode` scene, 2π/ω_n with ω_n from the n-th zero
    /// of J₀ (D. Bernoulli); `None` for a release.
    pub fn mode_period(&self) -> Option<f64> {
        match *self {
            Self::Mode { number, .. } => {
                Some(std::f64::consts::TAU / bessel::mode_frequency(number))
            }
            Self::Release { .. } | Self::Fold { .. } => None,
        }
    }

    /// How far the tip of a release strays from free fall at time `time`: the string beyond
    /// the travelling bend stays straight, so across its initial line the tip falls exactly
    /// as a body, −sin φ₀ x + cos φ₀ y = cos φ₀ t²/2 (y down), until the bend reaches it
    /// (about t ≈ 1.2). `None` for a mode, which starts hanging.
    pub fn free_fall_gap(&self, time: f64, tip_x: f64, tip_y: f64) -> Option<f64> {
        match *self {
            Self::Release { angle_deg } => {
                let (sin, cos) = angle_deg.to_radians().sin_cos();
                Some((-sin * tip_x + cos * tip_y - cos * time * time / 2.0).abs())
            }
            Self::Mode { .. } | Self::Fold { .. } => None,
        }
    }

    /// The scene's theory in a few sentences, for the viewer's Parameters: what its plots
    /// hold the motion against. `None` for a scene whose checks are in the summary only.
    pub fn theory_note(&self) -> Option<String> {
        match *self {
            Self::Fold { gap } => Some(format!(
                "**Theory** (Calkin & March, Am. J. Phys. 57, 154 (1989)), x the free end's fall: an energy-conserving string's free end moves at v² = x (2 − x)/(1 − x), faster than free fall's 2x, and the support pulls with (1 + x)/2 + v²/4 of the weight; the whole fall takes {:.3} (free fall: {:.3}). The plots show each beside the run, at the run's own x, until the snap. The theory is for no gap; this one is {gap}, and the bend needs N ≥ 2/gap.",
                fold::time_to_fall(1.0),
                2f64.sqrt()
            )),
            Self::Release { .. } | Self::Mode { .. } => None,
        }
    }

    /// What the scene's theory predicts of the motion `reading` measures, beside the
    /// measurement: for a fold, the free end's fall, its speed and the support's tension
    /// against Calkin & March's string ([`fold`]); nothing for a release or a mode, whose
    /// checks are in the summary. The predictions at the measured fall stop once the
    /// theory's free end has reached the bottom (its speed has no bound there, and the real
    /// chain's end snaps and rebounds).
    pub fn theory(&self, reading: &Reading) -> Vec<Comparison> {
        match *self {
            Self::Fold { .. } => {
                let x = reading.tip.y - reading.initial_tip.y;
                // Calkin & March's fall at this time: 1 once their chain hangs straight.
                let theirs = fold::fall_at(reading.time);
                let before_snap = (theirs < 1.0 && x < 0.999).then_some(x.max(0.0));
                let at_fall = |f: fn(f64) -> f64| before_snap.map(f);
                vec![
                    Comparison::new(Comparison::FALL, x)
                        .predicted("Calkin–March", Some(theirs))
                        .predicted("free fall", Some(reading.time * reading.time / 2.0)),
                    Comparison::new(Comparison::SPEED, reading.tip_velocity.norm())
                        .predicted("Calkin–March at this fall", at_fall(fold::speed))
                        .predicted("free fall at this fall", at_fall(fold::free_fall_speed)),
                    Comparison::new(Comparison::SUPPORT_TENSION, reading.support_tension)
                        .predicted(
                            "(1 + x)/2 + v²/4 at this fall",
                            at_fall(fold::support_tension),
                        ),
                    Comparison::new(Comparison::MOMENTUM, reading.momentum.y)
                        .predicted("(1 − x) v/2 at this fall", at_fall(fold::momentum)),
                ]
            }
            Self::Release { .. } | Self::Mode { .. } => Vec::new(),
        }
    }

    /// Angles φ_i of `segments` equal segments, sampled at the segment centres s = (i + ½)h.
    pub fn initial_angles(&self, segments: usize) -> Vec<f64> {
        let h = 1.0 / segments as f64;
        match *self {
            Self::Release { angle_deg } => vec![angle_deg.to_radians(); segments],
            Self::Mode { number, amplitude } => {
                let omega = bessel::mode_frequency(number);
                (0..segments)
                    .map(|i| {
                        let s = (i as f64 + 0.5) * h;
                        let r = (1.0 - s).sqrt();
                        // Sideways displacement x(s) = A J0(2ω sqrt(1 − s)) (zero at the
                        // support since J0(2ω) = 0); x = ∫ cos φ ≈ −∫ δφ, so δφ = −dx/ds.
                        let dx_ds = amplitude * omega * bessel::j1(2.0 * omega * r) / r;
                        FRAC_PI_2 - dx_ds
                    })
                    .collect()
            }
            Self::Fold { gap } => fold_angles(gap, segments),
        }
    }
}

/// The U of a fold cut into `segments` equal rods: rod i points along the chord of the U's
/// piece from arc length s = i h to (i + 1) h, so the straight arms are exact and each rod on
/// the half circle is parallel to its arc (the chord of a circular arc is parallel to the
/// tangent at its middle). The rods are h long where the chords around the bend are a little
/// shorter, so the free end starts within O(h²/d) of the support's height.
fn fold_angles(gap: f64, segments: usize) -> Vec<f64> {
    let radius = gap / 2.0;
    // Each arm's length: the half circle takes π d / 2 of the unit string.
    let arm = (1.0 - PI * radius) / 2.0;
    // The U at arc length s (x away from the support, y down): down the held arm, round the
    // half circle centred at (r, arm), up the free arm at x = d.
    let point = |s: f64| -> (f64, f64) {
        if s <= arm {
            (0.0, s)
        } else if s <= arm + PI * radius {
            let theta = (s - arm) / radius;
            (radius * (1.0 - theta.cos()), arm + radius * theta.sin())
        } else {
            (gap, arm - (s - arm - PI * radius))
        }
    };
    let h = 1.0 / segments as f64;
    (0..segments)
        .map(|i| {
            let (a, b) = (point(i as f64 * h), point((i + 1) as f64 * h));
            (b.1 - a.1).atan2(b.0 - a.0)
        })
        .collect()
}

/// The scene in words, as every output names it: "release at 30°",
/// "mode 1 (tip amplitude 0.05)".
impl std::fmt::Display for Scene {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            Self::Release { angle_deg } => write!(f, "release at {angle_deg}°"),
            Self::Mode { number, amplitude } => {
                write!(f, "mode {number} (tip amplitude {amplitude})")
            }
            Self::Fold { gap } => write!(f, "fold (gap {gap})"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_fold_starts_at_the_support_s_height_with_its_arms_apart_by_its_gap() {
        let (gap, n) = (0.02, 200);
        let angles = Scene::Fold { gap }.initial_angles(n);
        let tip = super::super::geometry::tip(&angles);
        // Symmetric U and cut: the free end at the support's height; the rods round the bend
        // are longer than their chords, so it sits a little further out than the gap.
        assert!(tip.y.abs() < 1e-12, "{tip:?}");
        assert!(tip.x > gap && tip.x < 1.02 * gap, "{tip:?}");
        // Straight down, round the bend, straight up.
        assert_eq!(angles[0], FRAC_PI_2);
        assert_eq!(angles[n - 1], -FRAC_PI_2);
    }

    #[test]
    fn a_fold_names_its_theory_for_the_viewer_and_a_release_has_none() {
        let note = Scene::Fold { gap: 0.04 }.theory_note().unwrap();
        assert!(
            note.contains("Calkin & March") && note.contains("1.198"),
            "{note}"
        );
        assert!(Scene::Release { angle_deg: 30.0 }.theory_note().is_none());
    }
}
