//! A frame: one logged instant of a run, the rope's shape and everything the viewer and the
//! summary show of it, built from a method's state ([`frame`]), and the energies its
//! deviation and balance are measured from ([`EnergyBase`]).

use super::estimate::ErrorEstimate;
use super::trust::reference_energy;
use crate::methods::{Method, Observation};
use crate::model::Energy;
use crate::model::geometry::{self, Point};
use crate::model::support::{self, SupportNow};
use nalgebra::Vector2;

/// One logged instant: the rope's shape and everything the viewer and the summary show.
#[derive(Clone, Debug)]
pub struct Frame {
    pub step: u64,
    pub time: f64,
    /// Node positions in the room, support … tip (N + 1 points, eqs. 14–15, from the
    /// support where it is now).
    pub nodes: Vec<Point>,
    /// Where each node sits along the string (s = 0 at the support, 1 at the tip) for rods of
    /// unequal lengths ([`Method::lengths`]); `None` for equal segments, node i at i/N.
    pub edges: Option<Vec<f64>>,
    /// Tension on each segment, the first at [`Frame::tension_first_at`] segments from the
    /// support, the others a segment apart.
    pub tension: Vec<f64>,
    /// Where the first tension sits, in segments from the support
    /// ([`crate::methods::Descriptor::tension_first_at`]).
    pub tension_first_at: f64,
    /// In the room: under a shaken support, the kinetic energy of its motion included.
    pub energy: Energy,
    /// (E − W − E_ref) / scale, E_ref the same after [`REFERENCE_STEP`](super::trust::REFERENCE_STEP) steps, W the work the
    /// support has done (none unless it moves).
    pub energy_deviation: f64,
    /// A moving support: where it is, how it moves, and the work it has done since the
    /// start; `None` for a fixed one.
    pub support: Option<SupportNow>,
    /// E − E₀ − W, E₀ the energy at the start: what the energy gained beyond the support's
    /// work (zero for the ideal string); `None` under a fixed support, where it is E − E₀.
    pub balance: Option<f64>,
    pub tip_velocity: Vector2<f64>,
    pub tip_acceleration: Vector2<f64>,
    /// The string's momentum (mass 1, [`geometry::momentum`]): what the support's force
    /// changes, beside gravity.
    pub momentum: Vector2<f64>,
    /// The tension at the support, s = 0 ([`Method::support_tension`]): the first of
    /// `tension` sits below it.
    pub support_tension: f64,
    /// The largest joint gap, for a method that solves for its joints (see
    /// [`Method::constraint_residual`]).
    pub constraint_residual: Option<f64>,
    /// |G v| before the latest velocity projection, for a method whose velocities can leave
    /// the constraints between projections (see [`Method::velocity_residual`]).
    pub velocity_residual: Option<f64>,
    /// Richardson's estimate of this frame's error, for a run with a shadow at an instant the
    /// shadow shares.
    pub error_estimate: Option<ErrorEstimate>,
    /// On the first frame at or after the instant the tip estimate first passed the
    /// tolerance (watched at every step the run shares with its shadow, frames or none): that
    /// instant and the estimate there.
    pub tolerance_exceeded: Option<Exceeded>,
    /// In a run of several methods side by side: which one this frame is of, and how far its
    /// string is from the most accurate one's. `None` in a run of one method.
    pub lane: Option<Lane>,
    /// What the scene's theory predicts of this frame's motion, beside the measurement
    /// ([`Scene::theory`](crate::model::Scene::theory)); empty for a scene without one.
    pub theory: Vec<crate::model::theory::Comparison>,
}

/// The instant a run's tip estimate first passed its tolerance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Exceeded {
    pub step: u64,
    pub time: f64,
    /// The tip's bound there (the run's `TipBound`), which passed the tolerance.
    pub estimate: f64,
}

/// A frame's place in a run of several methods side by side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lane {
    /// Where the method stands in the run's list (the plans of `FrameSink::begin_lanes`).
    pub index: usize,
    pub method: crate::methods::MethodKind,
    /// The largest distance, at equal arc length, between this string and that of the most
    /// accurate method still running (`MethodKind::BY_ACCURACY`); `None` for that one.
    pub disagreement: Option<f64>,
}

impl Frame {
    /// The free end.
    pub fn tip(&self) -> Point {
        self.nodes.last().copied().unwrap_or_else(Point::origin)
    }

    /// Where `tension[i]` sits along the string, s = 0 at the support and 1 at the tip,
    /// [`Frame::tension_first_at`] of its own segment along (graded rods: of its own rod).
    pub fn tension_s(&self, i: usize) -> f64 {
        match &self.edges {
            None => (i as f64 + self.tension_first_at) / self.tension.len() as f64,
            Some(e) => e[i] + self.tension_first_at * (e[i + 1] - e[i]),
        }
    }
}

/// The energies a frame's deviation and balance are measured from: E − W after
/// [`REFERENCE_STEP`](super::trust::REFERENCE_STEP) steps and at the start, and what deviations are divided by.
#[derive(Clone, Copy, Debug)]
pub struct EnergyBase {
    pub reference: f64,
    pub start: f64,
    pub scale: f64,
}

impl EnergyBase {
    /// The base of a run of `method` from its start, its reference measured ahead on a copy
    /// ([`reference_energy`]).
    pub fn of(method: &dyn Method) -> Self {
        Self::measured(method.energy_less_work(), reference_energy(method))
    }

    /// The base as the start knows it: the reference taken as the start's energy until the
    /// run reaches [`REFERENCE_STEP`](super::trust::REFERENCE_STEP), where [`run_watched`](super::simulate::run_watched) measures it.
    pub fn at_start(method: &dyn Method) -> Self {
        let start = method.energy_less_work();
        Self::measured(start, start)
    }

    /// The base of a run that started at energy `start` (E − W) and measured `reference`.
    pub(super) fn measured(start: f64, reference: f64) -> Self {
        let scale = if reference.abs() >= 0.01 {
            reference.abs()
        } else {
            1.0
        };
        Self {
            reference,
            start,
            scale,
        }
    }

    /// (E − W − E_ref) / scale of `energy` under `support`.
    pub(super) fn deviation(&self, energy: &Energy, support: Option<SupportNow>) -> f64 {
        (energy.total() - support.map_or(0.0, |s| s.work) - self.reference) / self.scale
    }
}

/// Builds a frame from the method's current state.
pub fn frame(method: &mut dyn Method, obs: &mut Observation, base: EnergyBase) -> Frame {
    method.observe(obs);
    let support = method.support();
    let lengths = method.lengths();
    let mut nodes = Vec::with_capacity(obs.angle.len() + 1);
    let motion = geometry::motion_of(
        &obs.angle,
        Some(&obs.tangent),
        &obs.angular_velocity,
        &obs.angular_acceleration,
        lengths,
        &mut nodes,
    );
    let edges = lengths.map(|l| {
        let mut edges = Vec::with_capacity(l.len() + 1);
        geometry::edges(l.len(), Some(l), &mut edges);
        edges
    });
    support::into_the_room(support, &mut nodes);
    let moving = Vector2::new(support.map_or(0.0, |s| s.velocity), 0.0);
    let energy = method.energy();
    let first_at = method.descriptor().tension_first_at;
    let kept = energy.total() - support.map_or(0.0, |s| s.work);
    Frame {
        step: method.steps(),
        time: method.time(),
        nodes,
        edges,
        tension: obs.tension.clone(),
        tension_first_at: first_at,
        energy,
        energy_deviation: base.deviation(&energy, support),
        balance: support.map(|_| kept - base.start),
        support,
        tip_velocity: motion.tip_velocity + moving,
        momentum: motion.momentum + moving,
        tip_acceleration: motion.tip_acceleration
            + Vector2::new(support.map_or(0.0, |s| s.acceleration), 0.0),
        support_tension: method.support_tension(),
        constraint_residual: method.constraint_residual(),
        velocity_residual: method.velocity_residual(),
        error_estimate: None,
        tolerance_exceeded: None,
        lane: None,
        theory: Vec::new(),
    }
}
