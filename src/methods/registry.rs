//! The methods a run can choose by name, and everything each says of itself. The rest of the
//! crate asks a [`MethodKind`] for its [`Descriptor`] and never matches on the method.

use super::method::{Descriptor, Method};
use super::{chain, graded, midpoint, rattle, seed};
use crate::error::ConfigError;
use crate::model::Scene;

/// The methods a run can choose by name.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "app", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum MethodKind {
    /// The report's finite-difference scheme: first order in h, explicit, cannot start from
    /// the horizontal.
    Seed,
    /// A chain of N uniform rigid rods, joint forces from an O(N) block-tridiagonal solve,
    /// RK4 in time: second order in h, exact inextensibility, starts from the horizontal.
    Chain,
    /// The chain's method on N rods graded towards the free end (s_i = 1 − (1 − i/N)^1.5),
    /// which resolve the whip of a falling string: from releases only.
    Graded,
    /// The same chain of rods in maximal coordinates, RATTLE in time: second order in h and
    /// in k, symplectic and time-reversible (no energy drift between the violent snaps of a
    /// long chaotic swing), starts from the horizontal.
    Rattle,
    /// The same chain of rods, an energy–momentum (discrete-gradient) midpoint rule in time:
    /// second order in h and in k, the energy kept exactly whatever the sequence of steps, so
    /// its steps shrink where the free end whips and grow again; starts from the horizontal.
    Midpoint,
}

impl MethodKind {
    /// Every method, in the order charts list them.
    pub const ALL: [MethodKind; 5] = [
        MethodKind::Seed,
        MethodKind::Chain,
        MethodKind::Graded,
        MethodKind::Rattle,
        MethodKind::Midpoint,
    ];

    /// The methods a study compares when none are named: those of a steady cost per step
    /// ([`Descriptor::steady_cost`]). The graded rods are studied when named: near the
    /// horizontal and over long runs their spinning end rods cost many times what the cost
    /// model predicts, and the study's grid would take far longer than it says.
    pub const STUDIED: [MethodKind; 4] = [
        MethodKind::Seed,
        MethodKind::Chain,
        MethodKind::Rattle,
        MethodKind::Midpoint,
    ];

    /// The method of a finite run when none is named: the report's.
    pub const DEFAULT: MethodKind = MethodKind::Seed;

    /// The method of a run left running (endless, looping or served) when none is named:
    /// the seed scheme diverges after some tens of time units at any step, the chain's
    /// energy drifts down and `rattle`'s jumps at violent snaps; `midpoint` keeps the energy
    /// at every frame, at about three quarters of the chain's cost per time unit.
    pub const DEFAULT_LASTING: MethodKind = MethodKind::Midpoint;

    /// Why [`Self::DEFAULT_LASTING`] is the default for a run left running, as the run and its
    /// summary say it.
    pub const DEFAULT_LASTING_BECAUSE: &str = "it keeps the energy at every frame, at about three quarters of the chain's cost per time unit";

    /// The scenes with a method of their own when none is named: the scene's name, the
    /// method, and why, as the run and its summary say it. The fold ends in a snap, the free
    /// end whipping the last rods round at thousands of radians a time unit, and `midpoint`
    /// keeps the energy through it to round-off (`tests/fold_physics.rs`); under a shaken
    /// support it keeps the energy balance (`tests/shake_physics.rs`).
    pub const SCENE_DEFAULTS: [(&str, MethodKind, &str); 2] = [
        (
            "fold",
            MethodKind::Midpoint,
            "it keeps the energy through the final snap to round-off, where the report's scheme diverges in the first second, rattle's energy jumps and the chain's drifts",
        ),
        (
            "shake",
            MethodKind::Midpoint,
            "it keeps the balance E − E₀ − W of the string's energy and the support's work to round-off (the shaken frame's gravity taken at each step's middle), where the chain's and rattle's drift; the report's scheme cannot carry a moving support",
        ),
    ];

    /// The method of the scene named `scene` when none is named, and why, if it has one of
    /// its own ([`Self::SCENE_DEFAULTS`]).
    pub fn scene_default(scene: &str) -> Option<(MethodKind, &'static str)> {
        Self::SCENE_DEFAULTS
            .iter()
            .find(|(name, ..)| *name == scene)
            .map(|&(_, method, because)| (method, because))
    }

    /// The method `rope study` computes its converged reference with: of a known, whole order
    /// in h (Richardson's extrapolation needs one) and with no stability limit to respect.
    pub const REFERENCE: MethodKind = MethodKind::Chain;

    /// The methods from the most accurate to the least, for a run that compares several: the
    /// highest-ranked of a comparison is the one the others' disagreement is measured from.
    /// The graded rods first (the chain's RK4 on rods that resolve the whip), then the chain:
    /// the study's reference (RK4 is fourth order in k, so at its default step its error is
    /// the rods' spatial one); then `midpoint` (energy exact), then `rattle` (second order in
    /// k), then the report's first-order scheme.
    pub const BY_ACCURACY: [MethodKind; 5] = [
        MethodKind::Graded,
        MethodKind::Chain,
        MethodKind::Midpoint,
        MethodKind::Rattle,
        MethodKind::Seed,
    ];

    /// Where the method stands in [`MethodKind::BY_ACCURACY`] (0 the most accurate).
    pub fn accuracy_rank(self) -> usize {
        Self::BY_ACCURACY
            .iter()
            .position(|&m| m == self)
            .unwrap_or(Self::BY_ACCURACY.len())
    }

    /// What the method says of itself: the registry, one line per method.
    pub fn descriptor(self) -> &'static Descriptor {
        match self {
            Self::Seed => &seed::DESCRIPTOR,
            Self::Chain => &chain::DESCRIPTOR,
            Self::Graded => &graded::DESCRIPTOR,
            Self::Rattle => &rattle::DESCRIPTOR,
            Self::Midpoint => &midpoint::DESCRIPTOR,
        }
    }

    /// The method chosen when none is named: for a run left running (`lasts`: endless,
    /// looping or served), or for one that ends.
    pub fn default_for(lasts: bool) -> MethodKind {
        if lasts {
            Self::DEFAULT_LASTING
        } else {
            Self::DEFAULT
        }
    }

    /// The name used on the command line and in summaries.
    pub fn name(self) -> &'static str {
        self.descriptor().name
    }

    /// Estimated largest stable time step at `segments` segments.
    pub fn stability_limit(self, segments: usize) -> f64 {
        self.descriptor().stability_limit(segments)
    }

    /// A stable time step that is accurate for this method at `segments` segments.
    pub fn default_dt(self, segments: usize) -> f64 {
        self.descriptor().default_dt(segments)
    }

    /// The default time step in `scene` at `segments` segments: what a run takes when `--dt`
    /// is not given ([`Descriptor::default_step`]).
    pub fn default_step(self, scene: &Scene, segments: usize) -> f64 {
        self.descriptor().default_step(scene, segments)
    }

    /// The step `--tolerance` runs this method at with `segments` segments.
    pub fn tolerance_dt(self, segments: usize) -> f64 {
        self.descriptor().tolerance_dt(segments)
    }

    /// Whether the method can start from `scene`, at any N and k: the scene's own validity,
    /// then [`Descriptor::starts_from`]. What building the method would refuse for the scene,
    /// without building it (validating the midpoint at N = 8 by a throwaway build at its
    /// fewest segments took 15 000 instructions, 4 % of the run: `examples/run_alone`).
    pub fn starts_from(self, scene: &Scene) -> Result<(), ConfigError> {
        scene.validate()?;
        (self.descriptor().starts_from)(scene)
    }

    /// Builds the method for `scene`, validating everything it needs.
    pub fn build(
        self,
        scene: &Scene,
        segments: usize,
        dt: f64,
    ) -> Result<Box<dyn Method>, ConfigError> {
        (self.descriptor().build)(scene, segments, dt)
    }
}

impl std::fmt::Display for MethodKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// A run of the report, to compare with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReportSetting {
    pub method: MethodKind,
    pub segments: usize,
    pub dt: f64,
}

/// The report's own setting: its scheme at N = 100, k = 1e-5.
pub const REPORT: ReportSetting = ReportSetting {
    method: MethodKind::Seed,
    segments: 100,
    dt: 1e-5,
};

#[cfg(test)]
mod tests {
    use super::MethodKind;
    use crate::model::{Scene, ShakeStart, geometry};

    /// What a method's `starts_from` refuses is what building it refuses, at a valid N and k,
    /// scene by scene: the check a run passes before it is built cannot drift from the
    /// builder's own.
    #[test]
    fn a_method_starts_from_the_scenes_it_builds_from() {
        let scenes = [
            Scene::Release { angle_deg: 0.0 },
            Scene::Release { angle_deg: 30.0 },
            Scene::Release { angle_deg: 90.0 },
            Scene::Release { angle_deg: 120.0 },
            Scene::Mode {
                number: 2,
                amplitude: 0.05,
            },
            Scene::Fold { gap: 0.04 },
            Scene::Shake {
                amplitude: 0.01,
                frequency: 2.0,
                start: ShakeStart::Steady,
            },
        ];
        let mut refused = 0;
        for kind in MethodKind::ALL {
            for scene in &scenes {
                let n = 40;
                let built = kind.build(scene, n, kind.default_dt(n)).err();
                refused += usize::from(built.is_some());
                assert_eq!(kind.starts_from(scene).err(), built, "{kind} from {scene}");
            }
        }
        // The angle past 90° for all five; seed from the horizontal, a fold and a shake; the
        // graded rods from a mode, a fold and a shake.
        assert_eq!(refused, 5 + 3 + 3);
    }

    /// Where a method sums its free end from what it holds (tangents turned or carried with
    /// its angles), that is the sum of its angles' sines and cosines, to round-off, at every
    /// step: the live estimate reads it there.
    #[test]
    fn every_methods_tip_is_the_tip_of_its_angles() {
        let scene = Scene::Release { angle_deg: 30.0 };
        for kind in MethodKind::ALL {
            let n = 40;
            let mut method = kind.build(&scene, n, kind.default_dt(n)).expect("builds");
            let mut worst: f64 = 0.0;
            for _ in 0..400 {
                method.step().expect("steps");
                let angles = geometry::tip_of(method.angles(), method.lengths());
                worst = worst.max((method.tip() - angles).norm());
            }
            assert!(worst < 1e-13, "{kind}: the tip strays by {worst:e}");
        }
    }
}
