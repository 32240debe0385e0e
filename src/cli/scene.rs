//! The scene flags `rope run` and `rope study` share: which initial state, from which
//! angle or mode.

use crate::error::ConfigError;
use crate::model::{Scene, ShakeStart};

/// The scene flags shared by `run` and `study`.
#[derive(Debug, clap::Args)]
pub struct SceneArgs {
    /// Initial state.
    #[arg(long, value_enum, default_value_t = SceneKind::Release)]
    pub scene: SceneKind,

    /// Initial angle below the horizontal, in degrees (release scene), 0 to 90 [default: 30].
    /// `rope run` takes a list (e.g. the report's 30,60,90) and runs the scenes one after
    /// another.
    #[arg(
        long,
        value_delimiter = ',',
        allow_negative_numbers = true,
        allow_hyphen_values = true
    )]
    pub angle: Vec<f64>,

    /// Which small-oscillation mode the `mode` scene starts in (1 to 4) [default: 1]; `rope run`
    /// takes a list, as for --angle.
    #[arg(long, value_delimiter = ',')]
    pub mode_number: Vec<u32>,

    /// Tip displacement of the `mode` scene, in string lengths (|A| ≤ 0.2) [default: 0.05];
    /// for the `shake` scene, the support's sideways amplitude (0 < A ≤ 0.05) [default:
    /// 0.01].
    #[arg(long, allow_negative_numbers = true, allow_hyphen_values = true)]
    pub amplitude: Option<f64>,

    /// How fast the `shake` scene's support moves, Ω in x_s = A sin Ωt (radians per time
    /// unit, g = L = 1; 0 < Ω ≤ 20) [default: 2.0]. Resonances at 1.2024, 2.7600, 4.3269, …;
    /// `rope run` takes a list, as for --angle.
    #[arg(
        long,
        value_delimiter = ',',
        allow_negative_numbers = true,
        allow_hyphen_values = true
    )]
    pub frequency: Vec<f64>,

    /// A sweep of the `shake` scene's frequency, Ω₁..Ω₂ or Ω₁..Ω₂:count (count frequencies
    /// evenly spaced, ends included [default: 100]), each run in turn: e.g. 0.2..5:120 with
    /// --from rest shows the resonances appear one after another.
    #[arg(long, conflicts_with = "frequency")]
    pub sweep: Option<String>,

    /// How the `shake` scene starts: on the linear steady state (periodic from the first
    /// frame), or hanging at rest.
    #[arg(long = "from", value_enum)]
    pub start: Option<StartKind>,

    /// How far apart the two ends of the `fold` scene start, in string lengths (0 < d < 2/π)
    /// [default: 0.04]. Its bend is a half circle of this diameter: give --segments at least
    /// 2 / gap so that two rods or more span it.
    #[arg(long, allow_negative_numbers = true, allow_hyphen_values = true)]
    pub gap: Option<f64>,
}

impl SceneArgs {
    /// The release angle when none is given.
    pub const DEFAULT_ANGLE: f64 = 30.0;
    /// The mode when none is given.
    pub const DEFAULT_MODE: u32 = 1;
    /// The mode's tip displacement when none is given.
    pub const DEFAULT_AMPLITUDE: f64 = 0.05;
    /// The fold's gap when none is given: four rods across it at the default N = 100, and
    /// narrow enough for Calkin & March's limit of no gap.
    pub const DEFAULT_GAP: f64 = 0.04;
    /// The shaken support's amplitude when none is given: the free end then swings a few
    /// hundredths at the default frequency, small enough for the linear theory, large enough
    /// to see.
    pub const DEFAULT_SHAKE_AMPLITUDE: f64 = 0.01;
    /// The shaking frequency when none is given: between the first two resonances.
    pub const DEFAULT_FREQUENCY: f64 = 2.0;
    /// Frequencies in a sweep when the count is not given.
    pub const DEFAULT_SWEEP_COUNT: usize = 100;

    /// The scenes the flags describe, in the order given. A flag of the other scene is
    /// refused, naming it, rather than silently ignored.
    pub fn scenes(&self) -> Result<Vec<Scene>, ConfigError> {
        // Each scene's own flags; one given to another scene is named, the first in this order.
        let given: [(_, _, &[SceneKind]); 7] = [
            ("gap", self.gap.is_some(), &[SceneKind::Fold]),
            ("angle", !self.angle.is_empty(), &[SceneKind::Release]),
            (
                "mode-number",
                !self.mode_number.is_empty(),
                &[SceneKind::Mode],
            ),
            (
                "amplitude",
                self.amplitude.is_some(),
                &[SceneKind::Mode, SceneKind::Shake],
            ),
            ("frequency", !self.frequency.is_empty(), &[SceneKind::Shake]),
            ("sweep", self.sweep.is_some(), &[SceneKind::Shake]),
            ("from", self.start.is_some(), &[SceneKind::Shake]),
        ];
        if let Some(&(flag, ..)) = given
            .iter()
            .find(|&&(_, is_given, owners)| is_given && !owners.contains(&self.scene))
        {
            return Err(ConfigError::ForeignSceneFlag {
                flag,
                scene: self.scene.name(),
            });
        }
        match self.scene {
            SceneKind::Release => {
                let angles = if self.angle.is_empty() {
                    &[Self::DEFAULT_ANGLE][..]
                } else {
                    &self.angle[..]
                };
                Ok(angles
                    .iter()
                    .map(|&angle_deg| Scene::Release { angle_deg })
                    .collect())
            }
            SceneKind::Mode => {
                let numbers = if self.mode_number.is_empty() {
                    &[Self::DEFAULT_MODE][..]
                } else {
                    &self.mode_number[..]
                };
                let amplitude = self.amplitude.unwrap_or(Self::DEFAULT_AMPLITUDE);
                Ok(numbers
                    .iter()
                    .map(|&number| Scene::Mode { number, amplitude })
                    .collect())
            }
            SceneKind::Fold => Ok(vec![Scene::Fold {
                gap: self.gap.unwrap_or(Self::DEFAULT_GAP),
            }]),
            SceneKind::Shake => {
                let frequencies = match &self.sweep {
                    Some(sweep) => parse_sweep(sweep)?,
                    None if self.frequency.is_empty() => vec![Self::DEFAULT_FREQUENCY],
                    None => self.frequency.clone(),
                };
                let amplitude = self.amplitude.unwrap_or(Self::DEFAULT_SHAKE_AMPLITUDE);
                let start = match self.start.unwrap_or(StartKind::Steady) {
                    StartKind::Steady => ShakeStart::Steady,
                    StartKind::Rest => ShakeStart::Rest,
                };
                Ok(frequencies
                    .into_iter()
                    .map(|frequency| Scene::Shake {
                        amplitude,
                        frequency,
                        start,
                    })
                    .collect())
            }
        }
    }

    /// The one scene a study is about, validated.
    pub fn scene(&self) -> Result<Scene, ConfigError> {
        match self.scenes()?.as_slice() {
            [scene] => {
                scene.validate()?;
                Ok(*scene)
            }
            scenes => Err(ConfigError::StudyScenes {
                flag: match self.scene {
                    SceneKind::Release => "angle",
                    SceneKind::Mode => "mode-number",
                    SceneKind::Fold => "gap",
                    SceneKind::Shake => "frequency",
                },
                count: scenes.len(),
            }),
        }
    }
}

/// Which initial state to start from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum SceneKind {
    /// Straight and at rest at --angle below the horizontal, then let go.
    Release,
    /// Hanging at rest, displaced by --amplitude in the shape of mode --mode-number.
    Mode,
    /// Folded in a U with both ends at the support's height, --gap apart; the free end is
    /// let go and falls faster than gravity (Calkin & March).
    Fold,
    /// Hanging, its support shaken sideways as --amplitude sin(--frequency t): the string's
    /// modes resonate one after another as the frequency sweeps past them.
    Shake,
}

/// How the `shake` scene starts.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum StartKind {
    /// On the linear steady state: periodic from the first frame.
    Steady,
    /// Hanging at rest: the steady state and the free modes together (at a resonance, the
    /// amplitude grows in proportion to time).
    Rest,
}

/// The frequencies of `--sweep Ω₁..Ω₂[:count]`, evenly spaced, both ends included.
fn parse_sweep(text: &str) -> Result<Vec<f64>, ConfigError> {
    let bad = |wrong: String| ConfigError::Sweep {
        text: text.to_string(),
        wrong,
    };
    let (range, count) = match text.split_once(':') {
        Some((range, count)) => (
            range,
            count.trim().parse::<usize>().map_err(|_| {
                bad(format!(
                    "the count \"{}\" is not a whole number",
                    count.trim()
                ))
            })?,
        ),
        None => (text, SceneArgs::DEFAULT_SWEEP_COUNT),
    };
    let (low, high) = range
        .split_once("..")
        .ok_or_else(|| bad("no \"..\" between the two frequencies".to_owned()))?;
    let number = |which: &str, typed: &str| {
        typed
            .trim()
            .parse::<f64>()
            .ok()
            .filter(|f| f.is_finite())
            .ok_or_else(|| bad(format!("{which} \"{}\" is not a number", typed.trim())))
    };
    let (low, high) = (number("Ω₁", low)?, number("Ω₂", high)?);
    let max = crate::model::scene::SHAKE_FREQUENCY_MAX;
    if low <= 0.0 {
        return Err(bad(format!("Ω₁ = {low} is not above 0")));
    }
    if low >= high {
        return Err(bad(format!("Ω₁ = {low} is not below Ω₂ = {high}")));
    }
    if high > max {
        return Err(bad(format!("Ω₂ = {high} is above {max}")));
    }
    if !(2..=2000).contains(&count) {
        return Err(bad(format!("the count {count} is not from 2 to 2000")));
    }
    let spacing = (high - low) / (count - 1) as f64;
    Ok((0..count).map(|i| low + i as f64 * spacing).collect())
}

impl SceneKind {
    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Self::Release => "release",
            Self::Mode => "mode",
            Self::Fold => "fold",
            Self::Shake => "shake",
        }
    }
}
