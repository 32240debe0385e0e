//! The step a method's tip needs ([`AccurateStep`]): for a method stable at any step, what
//! its default step is never below, by N and by how hard the scene's free end whips; and the
//! grid of frame instants such steps are brought onto ([`TOLERANCE_STEP_GRID`],
//! [`whole_division`]).

use crate::model::Scene;

/// What [`Descriptor::tolerance_dt`](super::Descriptor::tolerance_dt) divides into whole
/// steps: half the interval of the default 60 frames per time unit, so that each frame falls
/// on an even step.
pub const TOLERANCE_STEP_GRID: f64 = 1.0 / 120.0;

/// The largest step at most `dt` that divides `interval` into a whole number of steps (one
/// step of `interval` where `dt` is longer): what puts frames, or a shadow's shared steps,
/// exactly on steps.
pub fn whole_division(interval: f64, dt: f64) -> f64 {
    let steps = (interval / dt - 1e-9).ceil().max(1.0);
    interval / steps
}

/// The step a method's tip needs at N segments, at most `largest`:
/// k = `times_h` × h × (`from` / N)^`shrink`. Its time error grows as k² times a constant that
/// itself grows with N (a finer rope resolves a faster whip), against a spatial error that
/// falls as h, so past `from` the step falls faster than h. Below `largest` it is brought down
/// to 1/(120 m) for a whole m ([`TOLERANCE_STEP_GRID`]), as `--tolerance`'s steps are: frames
/// at 60, 30, 20, … per time unit then fall on even steps, which the live estimate's shadow
/// shares.
///
/// The rule is the horizontal release's, whose free end whips hardest. A release further
/// below the horizontal whips less, and its time error is a smaller share of its spatial
/// error: from `calm_from_deg` on, the step (and `largest`) is `calm_times` the rule's, and
/// between `whip_to_deg` and `calm_from_deg` the factor rises linearly from 1
/// ([`AccurateStep::ease`]). Every other scene takes the rule as it is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AccurateStep {
    pub times_h: f64,
    pub from: usize,
    pub shrink: f64,
    pub largest: f64,
    /// Up to this release angle (degrees below the horizontal) the rule as it is.
    pub whip_to_deg: f64,
    /// From this release angle on, `calm_times` the rule.
    pub calm_from_deg: f64,
    /// What a calm release's step is multiplied by.
    pub calm_times: f64,
}

impl AccurateStep {
    /// The step at `segments` segments for the horizontal release, or any scene whose whip
    /// is not known to be milder.
    pub fn at(&self, segments: usize) -> f64 {
        self.eased(segments, 1.0)
    }

    /// The step at `segments` segments in `scene`.
    pub fn in_scene(&self, scene: &Scene, segments: usize) -> f64 {
        self.eased(segments, self.ease(scene))
    }

    /// What the rule's step (and its `largest`) is multiplied by in `scene`: 1 up to
    /// `whip_to_deg`, `calm_times` from `calm_from_deg`, linear between; 1 for any scene
    /// but a release.
    pub fn ease(&self, scene: &Scene) -> f64 {
        match *scene {
            Scene::Release { angle_deg } => {
                let span = self.calm_from_deg - self.whip_to_deg;
                let along = ((angle_deg - self.whip_to_deg) / span).clamp(0.0, 1.0);
                1.0 + (self.calm_times - 1.0) * along
            }
            _ => 1.0,
        }
    }

    fn eased(&self, segments: usize, ease: f64) -> f64 {
        let n = segments.max(1) as f64;
        let wanted = ease * self.times_h / n * (self.from as f64 / n).powf(self.shrink);
        match wanted >= ease * self.largest {
            true => ease * self.largest,
            false => whole_division(TOLERANCE_STEP_GRID, wanted),
        }
    }

    /// The rule in a run's words: "0.8 h (1600 / N)^0.4 at most 1e-3".
    pub fn rule(&self) -> String {
        format!(
            "{} h ({} / N)^{} at most {:e}",
            self.times_h, self.from, self.shrink, self.largest
        )
    }

    /// The rule as `scene` takes it, in a run's words: "2 × (0.8 h (1600 / N)^0.4 at most
    /// 1e-3) (twice the horizontal release's rule: from 10° below the horizontal its free end
    /// whips less)".
    pub fn rule_in(&self, scene: &Scene) -> String {
        let ease = self.ease(scene);
        if ease == 1.0 {
            return self.rule();
        }
        // As a run prints it: 1.3, not 1.2999999999999998.
        let shown = (ease * 100.0).round() / 100.0;
        let (times, from) = match ease < self.calm_times {
            true => (
                format!("{shown} times"),
                format!(
                    "the factor rises from 1 at {}° to {} at {}°, as",
                    self.whip_to_deg, self.calm_times, self.calm_from_deg
                ),
            ),
            false => (
                match self.calm_times == 2.0 {
                    true => "twice".to_owned(),
                    false => format!("{} times", self.calm_times),
                },
                format!("from {}° below the horizontal", self.calm_from_deg),
            ),
        };
        format!(
            "{shown} × ({}) ({times} the horizontal release's rule: {from} its free end whips less)",
            self.rule()
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_run_reads_the_rule_as_its_scene_takes_it() {
        // The midpoint rule's: 0.8 h (1600 / N)^0.4 at most 1e-3, twice from 10°.
        let rule = crate::methods::midpoint::DESCRIPTOR.accurate_step;
        let rule = rule.expect("the midpoint rule has an accurate step");
        let release = |angle_deg| Scene::Release { angle_deg };
        assert_eq!(rule.rule_in(&release(0.0)), rule.rule());
        assert_eq!(rule.rule_in(&Scene::Fold { gap: 0.1 }), rule.rule());
        let calm = rule.rule_in(&release(30.0));
        assert!(
            calm.starts_with("2 × (0.8 h (1600 / N)^0.4 at most 1e-3) (twice"),
            "{calm}"
        );
        let between = rule.rule_in(&release(3.0));
        assert!(
            between.starts_with("1.3 × (") && between.contains("1.3 times"),
            "{between}"
        );
        // And the steps it names: 1.3 times the rule's at 3°, on the grid below the cap.
        let (k, k3) = (rule.at(1_000), rule.in_scene(&release(3.0), 1_000));
        assert!((k - 1.0 / 1_080.0).abs() < 1e-15 && (k3 - 1.0 / 840.0).abs() < 1e-15);
    }
}
