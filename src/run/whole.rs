//! A whole run in one call, for a program that embeds rope: a [`RunConfig`] in, every frame
//! and the summary out ([`simulate`]). What `rope run` does, without the recording.

use super::config::RunConfig;
use super::pipeline;
use super::simulate::Frame;
use super::summary::Summary;
use crate::error::ConfigError;

/// What [`simulate`] returns: every frame of the run and what the run measured.
#[derive(Clone, Debug)]
pub struct Simulated {
    /// The frames at `log_rate` a time unit, t = 0 first: the shape (`nodes`, y down), the
    /// tension, the energies, the tip's velocity, the live error estimate.
    pub frames: Vec<Frame>,
    /// What `rope run --summary` writes: the energy's largest deviation, the tip at the end,
    /// the largest support tension, the live error estimate, the scene's theory beside the
    /// motion, and how the run ended (`status`, `diverged`).
    pub summary: Summary,
}

/// Runs `config` to its end, with no viewer and no file: every frame is kept in memory
/// (`log_rate` frames a time unit; lower it for a long or fine run). A run that diverges
/// returns what it had, its summary saying when and why. `Err` for a configuration that
/// cannot run, naming the parameter and what would work.
///
/// ```
/// use rope::{MethodKind, RunConfig, Scene};
///
/// let run = rope::simulate(&RunConfig {
///     method: MethodKind::Midpoint,
///     scene: Scene::Release { angle_deg: 30.0 },
///     segments: 50,
///     duration: 1.0,
///     log_rate: 10.0,
///     ..RunConfig::default()
/// })?;
/// assert_eq!(run.frames.len(), 11); // t = 0, 0.1, …, 1
/// let end = run.frames.last().expect("the frame at t = 1");
/// let (tip, energy) = (end.tip(), end.energy.total());
/// println!("t = {}: tip at ({:.4}, {:.4}), energy {energy:.6}", end.time, tip.x, tip.y);
/// // The midpoint method keeps the energy to round-off.
/// assert!(run.summary.energy.max_rel_deviation < 1e-9);
/// # Ok::<(), rope::ConfigError>(())
/// ```
pub fn simulate(config: &RunConfig) -> Result<Simulated, ConfigError> {
    let (frames, summary) = pipeline::run_in_memory(&config.validate()?)?;
    Ok(Simulated { frames, summary })
}
