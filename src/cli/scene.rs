//! The scene flags `rope run` and `rope study` share: which initial state, from which
//! angle or mode.

use crate::error::ConfigError;
use crate::model::Scene;

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

    /// Tip displacement of the `mode` scene, in string lengths (|A| ≤ 0.2) [default: 0.05].
    #[arg(long, allow_negative_numbers = true, allow_hyphen_values = true)]
    pub amplitude: Option<f64>,

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

    /// The scenes the flags describe, in the order given. A flag of the other scene is
    /// refused, naming it, rather than silently ignored.
    pub fn scenes(&self) -> Result<Vec<Scene>, ConfigError> {
        // Each scene's own flags; one given to another scene is named, the first in this order.
        let given = [
            ("gap", self.gap.is_some(), SceneKind::Fold),
            ("angle", !self.angle.is_empty(), SceneKind::Release),
            ("mode-number", !self.mode_number.is_empty(), SceneKind::Mode),
            ("amplitude", self.amplitude.is_some(), SceneKind::Mode),
        ];
        if let Some(&(flag, ..)) = given
            .iter()
            .find(|&&(_, is_given, owner)| is_given && owner != self.scene)
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
}

impl SceneKind {
    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Self::Release => "release",
            Self::Mode => "mode",
            Self::Fold => "fold",
        }
    }
}
