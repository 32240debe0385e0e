//! Scenes: the initial states a run starts from, each a small function of the segment count.

use super::bessel;
use super::fold;
use super::support::{self, Support};
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
    /// Hanging straight down, its support shaken sideways, x_s(t) = `amplitude` sin(`frequency`
    /// t) ([`Support::Shaken`]); starting on the linear steady state or at rest.
    Shake {
        amplitude: f64,
        frequency: f64,
        start: ShakeStart,
    },
}

/// How a shaken string starts.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum ShakeStart {
    /// On the linear steady state, u(z, t) = A J₀(2Ω√z)/J₀(2Ω) sin Ωt at t = 0: hanging
    /// straight, every point moving sideways in step with the support, so that the motion is
    /// periodic from the first frame.
    Steady,
    /// Hanging still: the steady state and the free modes the start excites, together.
    Rest,
}

impl ShakeStart {
    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Self::Steady => "steady",
            Self::Rest => "rest",
        }
    }
}

/// The largest sideways amplitude of a shaken support, in string lengths: the theory the
/// scene is held against is linear.
pub const SHAKE_AMPLITUDE_MAX: f64 = 0.05;
/// The largest shaking frequency: past it the string's response is confined to a few rods
/// near the free end at any N a run can afford (the n-th mode has n − 1 nodes).
pub const SHAKE_FREQUENCY_MAX: f64 = 20.0;
/// The largest tip amplitude a steady start may ask for, in string lengths: nearer a
/// resonance the linear steady state is no longer small.
pub const STEADY_TIP_MAX: f64 = 0.2;

/// The largest gap a fold can have: at 2/π the half circle takes the whole string.
pub const FOLD_GAP_MAX: f64 = 2.0 / PI;

/// The widest gap at which a fold's comparisons with Calkin & March's string, a theory for no
/// gap, are trusted to about 1 %: at N = 200, `midpoint`'s free end was within 0.73 % of its
/// speed to a fall of 0.75 at d = 0.1, 2.9 % at 0.2, 7.4 % at 0.3 and 19 % at 0.4
/// (`docs/measurements.md`, "The fold's gap against its theory").
pub const FOLD_THEORY_GAP: f64 = 0.1;

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
            Self::Shake { .. } => "shake",
        }
    }

    /// How the support moves in this scene: fixed, but in a shake.
    pub fn support(&self) -> Support {
        match *self {
            Self::Shake {
                amplitude,
                frequency,
                ..
            } => Support::Shaken {
                amplitude,
                frequency,
            },
            Self::Release { .. } | Self::Mode { .. } | Self::Fold { .. } => Support::Fixed,
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
            Self::Shake {
                amplitude,
                frequency,
                start,
            } => {
                if !(amplitude > 0.0 && amplitude <= SHAKE_AMPLITUDE_MAX) {
                    return Err(ConfigError::ShakeAmplitude(amplitude));
                }
                if !(frequency > 0.0 && frequency <= SHAKE_FREQUENCY_MAX) {
                    return Err(ConfigError::ShakeFrequency(frequency));
                }
                let tip = support::free_end_swing(amplitude, frequency);
                if start == ShakeStart::Steady && tip > STEADY_TIP_MAX {
                    return Err(ConfigError::SteadyNearResonance {
                        frequency,
                        amplitude,
                        tip,
                        resonance: nearest_resonance(frequency),
                    });
                }
            }
        }
        Ok(())
    }

    /// The initial angle of the string at the support, in radians below the horizontal.
    pub fn support_angle(&self) -> f64 {
        match *self {
            Self::Release { angle_deg } => angle_deg.to_radians(),
            Self::Mode { .. } | Self::Fold { .. } | Self::Shake { .. } => FRAC_PI_2,
        }
    }

    /// The small-oscillation period of the `mode` scene, 2π/ω_n with ω_n from the n-th zero
    /// of J₀ (D. Bernoulli); `None` for a release.
    pub fn mode_period(&self) -> Option<f64> {
        match *self {
            Self::Mode { number, .. } => {
                Some(std::f64::consts::TAU / bessel::mode_frequency(number))
            }
            Self::Release { .. } | Self::Fold { .. } | Self::Shake { .. } => None,
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
            Self::Mode { .. } | Self::Fold { .. } | Self::Shake { .. } => None,
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
            Self::Shake {
                amplitude,
                frequency,
                ..
            } => Some(format!(
                "**Theory** (linear, D. Bernoulli's hanging string): shaken as x_s = A sin Ωt, the string answers with u(z, t) = A J₀(2Ω√z)/J₀(2Ω) sin Ωt, z the height above the free end, so the free end swings {:.4} (A/|J₀(2Ω)|, A = {amplitude}, Ω = {frequency}){}. It resonates where J₀(2Ω) = 0: ω₁ = {:.4}, ω₂ = {:.4}, ω₃ = {:.4}. The energy panel shows the support's work W and the balance E − E₀ − W, which an exact method keeps at zero.",
                support::free_end_swing(amplitude, frequency),
                if support::steady_response(frequency, 0.0) < 0.0 {
                    ", against the support's motion"
                } else {
                    ", with the support's motion"
                },
                bessel::mode_frequency(1),
                bessel::mode_frequency(2),
                bessel::mode_frequency(3),
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
            Self::Shake { .. } => self
                .sideways_prediction(reading.time)
                .map(|(name, predicted)| {
                    Comparison::new(Comparison::TIP_SIDEWAYS, reading.tip.x)
                        .predicted(name, Some(predicted))
                })
                .into_iter()
                .collect(),
            Self::Release { .. } | Self::Mode { .. } => Vec::new(),
        }
    }

    /// Whether the scene's theory compares the free end's fall ([`Comparison::FALL`], a
    /// fold's), at any reading: a run then reads the theory at every step, so that what its
    /// summary quotes does not depend on the frames.
    pub fn compares_falls(&self) -> bool {
        matches!(self, Self::Fold { .. })
    }

    /// For a shake, what linear theory predicts of the free end's sideways displacement at
    /// `time`, and the prediction's name: the steady state A sin Ωt / J₀(2Ω). The steady state
    /// is the motion of a steady start; from rest it is the part the shaking drives, beside the
    /// free modes the start excites. Near a resonance, where the steady state is no longer
    /// small, a start from rest grows instead: its envelope is linear theory's. `None` for a
    /// scene with a fixed support.
    pub fn sideways_prediction(&self, time: f64) -> Option<(&'static str, f64)> {
        let Self::Shake {
            amplitude,
            frequency,
            start,
        } = *self
        else {
            return None;
        };
        let response = support::steady_response(frequency, 0.0);
        Some(
            if start == ShakeStart::Rest && amplitude * response.abs() > STEADY_TIP_MAX {
                let n = resonance_number(frequency);
                let resonance = bessel::mode_frequency(n);
                let growth = support::resonant_growth_per_period(n, amplitude);
                (
                    "resonance's envelope, growing c_n π A a period",
                    growth * time * resonance / std::f64::consts::TAU,
                )
            } else {
                (
                    "steady state A sin Ωt / J₀(2Ω)",
                    amplitude * response * (frequency * time).sin(),
                )
            },
        )
    }

    /// Rates φ̇_i at the start, sampled at the segment centres as [`Scene::initial_angles`]:
    /// zero but for a shake started on its steady state, whose every point moves sideways at
    /// u̇ = AΩ J₀(2Ω√z)/J₀(2Ω) in the room, u̇ − AΩ in the support's frame. Hanging straight,
    /// x(s) = ∫ cos φ, so φ̇ = −d(u̇ − AΩ)/ds = −AΩ² J₁(2Ω√z) / (√z J₀(2Ω)), z = 1 − s.
    pub fn initial_rates(&self, segments: usize) -> Vec<f64> {
        match *self {
            Self::Shake {
                amplitude,
                frequency,
                start: ShakeStart::Steady,
            } => {
                let h = 1.0 / segments as f64;
                let scale = amplitude * frequency * frequency / bessel::j0(2.0 * frequency);
                (0..segments)
                    .map(|i| {
                        let r = (1.0 - (i as f64 + 0.5) * h).sqrt();
                        -scale * bessel::j1(2.0 * frequency * r) / r
                    })
                    .collect()
            }
            Self::Shake {
                start: ShakeStart::Rest,
                ..
            }
            | Self::Release { .. }
            | Self::Mode { .. }
            | Self::Fold { .. } => vec![0.0; segments],
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
            Self::Shake { .. } => vec![FRAC_PI_2; segments],
        }
    }
}

/// The resonance ω_n nearest `frequency`.
pub fn nearest_resonance(frequency: f64) -> f64 {
    bessel::mode_frequency(resonance_number(frequency))
}

/// n of the resonance ω_n nearest `frequency`: McMahon's ω_n ≈ (n − ¼)π/2 names the
/// candidate, and its neighbours settle it (the estimate is within a hundredth of ω_n).
pub fn resonance_number(frequency: f64) -> u32 {
    let guess = (2.0 * frequency / PI + 0.25).round().max(1.0) as u32;
    (guess.saturating_sub(1).max(1)..=guess + 1)
        .map(|n| (n, (bessel::mode_frequency(n) - frequency).abs()))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map_or(1, |(n, _)| n)
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
            Self::Shake {
                amplitude,
                frequency,
                start,
            } => {
                // A sweep's frequencies to four decimals, trailing zeros dropped.
                let omega = format!("{frequency:.4}");
                let omega = omega.trim_end_matches('0').trim_end_matches('.');
                write!(
                    f,
                    "shake (A = {amplitude}, Ω = {omega}, from {})",
                    start.name()
                )
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_scene_compares_falls_exactly_where_its_theory_has_a_fall() {
        use super::super::geometry::Point;
        use nalgebra::Vector2;
        let reading = Reading {
            time: 0.3,
            initial_tip: Point::new(0.02, 0.0),
            tip: Point::new(0.1, 0.2),
            tip_velocity: Vector2::new(0.1, 0.5),
            support_tension: 0.8,
            momentum: Vector2::new(0.0, 0.2),
        };
        let scenes = [
            Scene::Release { angle_deg: 30.0 },
            Scene::Fold { gap: 0.02 },
            Scene::Mode {
                number: 2,
                amplitude: 0.05,
            },
            Scene::Shake {
                amplitude: 0.05,
                frequency: 2.0,
                start: ShakeStart::Rest,
            },
        ];
        for scene in scenes {
            let theory = scene.theory(&reading);
            let has_fall = theory.iter().any(|c| c.quantity == Comparison::FALL);
            assert_eq!(scene.compares_falls(), has_fall, "{scene}");
        }
    }

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
    fn the_nearest_resonance_is_the_nearest_of_all_the_zeros() {
        for i in 0..2000 {
            let frequency = 0.01 + 0.01 * f64::from(i);
            let brute = (1..=60)
                .min_by(|&a: &u32, &b: &u32| {
                    let off = |n| (bessel::mode_frequency(n) - frequency).abs();
                    off(a).total_cmp(&off(b))
                })
                .unwrap();
            assert_eq!(resonance_number(frequency), brute, "Ω = {frequency}");
        }
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
