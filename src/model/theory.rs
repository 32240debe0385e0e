//! A scene's theory beside the motion: what a quantity measured at a frame is predicted to be,
//! by each prediction the scene knows. The run attaches these to its frames; the viewer draws
//! each quantity as a plot of the measurement and its predictions, and the summary reads
//! them at the instants the theory names.

use super::geometry::Point;
use nalgebra::Vector2;

/// What a frame measured that a theory can be held against.
#[derive(Clone, Copy, Debug)]
pub struct Reading {
    pub time: f64,
    /// The free end at t = 0.
    pub initial_tip: Point,
    pub tip: Point,
    pub tip_velocity: Vector2<f64>,
    /// The tension at the support, in units of the string's weight.
    pub support_tension: f64,
    /// The string's momentum (mass 1).
    pub momentum: Vector2<f64>,
}

/// One quantity at a frame: measured, and as each prediction has it (`None` where a
/// prediction says nothing, e.g. past the point its theory holds to).
#[derive(Clone, Debug, PartialEq)]
pub struct Comparison {
    /// What is measured, in words ([`Comparison::FALL`], …): the plot's title.
    pub quantity: &'static str,
    pub measured: f64,
    /// Each prediction's name and value.
    pub predictions: Vec<(&'static str, Option<f64>)>,
}

impl Comparison {
    /// How far the free end has fallen since t = 0.
    pub const FALL: &'static str = "fall of the free end";
    /// The free end's speed.
    pub const SPEED: &'static str = "speed of the free end";
    /// The tension at the support.
    pub const SUPPORT_TENSION: &'static str = "tension at the support";
    /// The string's downward momentum: its rate of change is the weight less the support's
    /// pull, so that its change over a window gives the support's pull averaged over it.
    pub const MOMENTUM: &'static str = "downward momentum";
    /// The free end's sideways displacement in the room.
    pub const TIP_SIDEWAYS: &'static str = "free end's sideways displacement";
    /// The support's pull averaged over the last stretch of time, from the change of the
    /// downward momentum: smooth where the raw tension jumps as each rod rounds a bend.
    pub const SUPPORT_PULL: &'static str = "support's pull, averaged";

    /// `quantity` measured at `measured`, with no prediction yet.
    pub fn new(quantity: &'static str, measured: f64) -> Self {
        Self {
            quantity,
            measured,
            predictions: Vec::new(),
        }
    }

    /// The same with the prediction `name` added.
    pub fn predicted(mut self, name: &'static str, value: Option<f64>) -> Self {
        self.predictions.push((name, value));
        self
    }

    /// The first prediction's value, if it says one.
    pub fn first_prediction(&self) -> Option<f64> {
        self.predictions.first().and_then(|&(_, v)| v)
    }
}
