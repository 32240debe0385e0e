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
}

impl SceneArgs {
    /// The release angle when none is given.
    pub const DEFAULT_ANGLE: f64 = 30.0;
    /// The mode when none is given.
    pub const DEFAULT_MODE: u32 = 1;
    /// The mode's tip displacement when none is given.
    pub const DEFAULT_AMPLITUDE: f64 = 0.05;

    /// The scenes the flags describe, in the order given. A flag of the other scene is
    /// refused, naming it, rather than silently ignored.
    pub fn scenes(&self) -> Result<Vec<Scene>, ConfigError> {
        let foreign = |flag: &'static str| ConfigError::ForeignSceneFlag {
            flag,
            scene: self.scene.name(),
        };
        match self.scene {
            SceneKind::Release => {
                if !self.mode_number.is_empty() {
                    return Err(foreign("mode-number"));
                }
                if self.amplitude.is_some() {
                    return Err(foreign("amplitude"));
                }
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
                if !self.angle.is_empty() {
                    return Err(foreign("angle"));
                }
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
}

impl SceneKind {
    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Self::Release => "release",
            Self::Mode => "mode",
        }
    }
}
