//! What the summary measures of the motion itself, on a fine grid that no `--log-rate`
//! moves: every step, or every [`FINE_GRID`](super::trust::FINE_GRID) of a time unit where
//! the steps are shorter, and the last step. The free fall of a released tip, a mode's
//! period, a shake's swing and energy balance, a fold's deepest fall: figures that would
//! otherwise change with the frames they were read at.

use super::shake_figures::{ShakeFigures, ShakeSample};
use super::simulate::EnergyBase;
use super::trust::steps_between;
use crate::methods::Method;
use crate::model::Scene;
use crate::model::analysis::ZeroCrossings;
use crate::model::support::point_in_the_room;
use serde::Serialize;

/// How long the free fall of a released tip is checked: well before the bend reaches the tip
/// (about t ≈ 1.2), where the chains of rods obey the law to round-off (`docs/physics.md`).
pub const FREE_FALL_UNTIL: f64 = 0.75;

/// The tip of a release against free fall (`Scene::free_fall_gap`), on the fine grid up to
/// `until`.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct FreeFall {
    pub until: f64,
    pub max_gap: f64,
}

/// How far a fold's free end fell, on the fine grid: its deepest and when, against where the
/// free arm runs out, a fall of 1 − πd/2 (the bend's half circle holds πd/2 of the chain; past
/// it the half circle swings down in the snap, and the end may fall further).
#[derive(Clone, Copy, Debug, Serialize)]
pub struct FoldFall {
    pub deepest_fall: f64,
    pub deepest_fall_time: f64,
    /// 1 − πd/2: where the free arm runs out.
    pub arm_limit: f64,
    /// The free end's height at the start, which the fall is measured from.
    #[serde(skip)]
    start: f64,
}

/// The summary's measurements of one run, taken on the fine grid as the run steps.
#[derive(Clone, Debug)]
pub struct Probes {
    scene: Scene,
    /// Steps between two instants of the grid ([`steps_between`]).
    every: u64,
    /// The run's last step, measured too.
    last: u64,
    /// E − W at the start, what a shake's balance is measured from.
    start_energy: f64,
    /// A release's tip against free fall.
    pub free_fall: Option<FreeFall>,
    /// The tip's sideways zero crossings, for a mode's period.
    crossings: ZeroCrossings,
    /// A shake's swing, its swing at Ω alone and its energy balance.
    pub shake: Option<ShakeFigures>,
    /// A fold's deepest fall.
    pub fold: Option<FoldFall>,
}

impl Probes {
    /// Nothing measured yet, of a run of `duration` at step `dt` from `scene`, whose energy
    /// at the start is `base.start`.
    pub fn new(scene: Scene, dt: f64, duration: f64, base: EnergyBase) -> Self {
        Self {
            scene,
            every: steps_between(dt),
            last: (duration / dt).round() as u64,
            start_energy: base.start,
            free_fall: None,
            crossings: ZeroCrossings::default(),
            shake: None,
            fold: None,
        }
    }

    /// Measures `method` where its step falls on the grid (call it at the start and after
    /// every step).
    pub fn step(&mut self, method: &dyn Method) {
        let step = method.steps();
        if !(step.is_multiple_of(self.every) || step == self.last) {
            return;
        }
        let time = method.time();
        let tip = || point_in_the_room(method.support(), method.tip());
        match self.scene {
            Scene::Release { .. } if time <= FREE_FALL_UNTIL => {
                let tip = tip();
                if let Some(gap) = self.scene.free_fall_gap(time, tip.x, tip.y) {
                    let worst = self.free_fall.map_or(0.0, |f| f.max_gap);
                    self.free_fall = Some(FreeFall {
                        until: time,
                        max_gap: worst.max(gap),
                    });
                }
            }
            Scene::Mode { .. } => self.crossings.push(time, tip().x),
            Scene::Shake { .. } => {
                let work = method.support().map_or(0.0, |s| s.work);
                let sample = ShakeSample {
                    time,
                    tip_x: tip().x,
                    balance: method.energy_less_work() - self.start_energy,
                    work,
                };
                ShakeFigures::push(&mut self.shake, self.scene, sample);
            }
            Scene::Fold { gap } => {
                let y = tip().y;
                let fold = self.fold.get_or_insert(FoldFall {
                    deepest_fall: 0.0,
                    deepest_fall_time: time,
                    arm_limit: crate::model::fold::arm_runs_out(gap),
                    start: y,
                });
                if y - fold.start > fold.deepest_fall {
                    (fold.deepest_fall, fold.deepest_fall_time) = (y - fold.start, time);
                }
            }
            Scene::Release { .. } => {}
        }
    }

    /// A mode's period from the tip's zero crossings (three at least, 1.25 periods).
    pub fn period(&self) -> Option<f64> {
        match self.scene {
            Scene::Mode { .. } => self.crossings.period(),
            _ => None,
        }
    }
}
