//! Scenes: the initial states a run starts from, each a small function of the segment count.

use super::bessel;
use crate::error::ConfigError;
use std::f64::consts::FRAC_PI_2;

/// An initial state of the string: angles of its segments, at rest.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum Scene {
    /// Straight and at rest at `angle_deg` degrees below the horizontal (the report's case).
    Release { angle_deg: f64 },
    /// Hanging straight down at rest, displaced by a small amplitude in the shape of the
    /// `number`-th small-oscillation mode (D. Bernoulli). `amplitude` is the tip's sideways
    /// displacement in string lengths.
    Mode { number: u32, amplitude: f64 },
}

impl Scene {
    /// Short name used on the command line and in summaries.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Release { .. } => "release",
            Self::Mode { .. } => "mode",
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
        }
        Ok(())
    }

    /// The initial angle of the string at the support, in radians below the horizontal.
    pub fn support_angle(&self) -> f64 {
        match *self {
            Self::Release { angle_deg } => angle_deg.to_radians(),
            Self::Mode { .. } => FRAC_PI_2,
        }
    }

    /// The small-oscillation period of the `mode` scene, 2π/ω_n with ω_n from the n-th zero
    /// of J₀ (D. Bernoulli); `None` for a release.
    pub fn mode_period(&self) -> Option<f64> {
        match *self {
            Self::Mode { number, .. } => {
                Some(std::f64::consts::TAU / bessel::mode_frequency(number))
            }
            Self::Release { .. } => None,
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
            Self::Mode { .. } => None,
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
        }
    }
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
        }
    }
}
