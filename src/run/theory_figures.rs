//! What the summary says of a scene's theory: each quantity the run compared
//! ([`crate::model::theory::Comparison`]) at every step, read at the instants the theory is
//! quoted at, so that what it quotes does not depend on the frames. For a
//! fold, where the free end has fallen 0.25, 0.5 and 0.75 of the length: its time, speed and
//! the support's tension, measured and predicted, each also averaged over the window of ±0.05
//! of that fall: the tension over the time the window spans, from the change of the string's
//! momentum (the raw tension jumps each time a rod rounds the bend).

use crate::model::theory::Comparison;
use serde::Serialize;

/// The falls at which a fold's summary quotes its theory.
pub const FOLD_FALLS: [f64; 3] = [0.25, 0.5, 0.75];

/// Half the window of fall over which a quantity is also averaged.
pub const FALL_WINDOW: f64 = 0.05;

/// How far the fall must come back from its largest for the free end to count as rebounded
/// from the snap (before it, the fall only grows).
const SNAP_REBOUND: f64 = 1e-3;

/// One quantity at one instant.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct QuantityAt {
    pub quantity: &'static str,
    /// Measured and predicted at the instant, each interpolated between the steps either
    /// side of it.
    pub measured: f64,
    pub predicted: Option<f64>,
    /// Measured and predicted, averaged over the steps within ±[`FALL_WINDOW`] of the fall.
    pub window_measured: f64,
    pub window_predicted: Option<f64>,
    /// measured / predicted − 1, and the same for the window's averages.
    pub relative_error: Option<f64>,
    pub window_relative_error: Option<f64>,
}

/// The theory read at one fall of the free end.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TheoryAt {
    pub fall: f64,
    /// When the free end got there (interpolated between steps).
    pub time: f64,
    /// Every quantity but the fall itself.
    pub quantities: Vec<QuantityAt>,
}

/// A frame's comparisons, kept while the fall is within reach of a quoted one.
#[derive(Clone, Debug)]
struct Kept {
    time: f64,
    fall: f64,
    values: Vec<(&'static str, f64, Option<f64>)>,
}

/// The frames a summary reads its theory from: those whose fall lies within
/// [`FALL_WINDOW`] of a quoted one (a bounded number: the fall passes each window once
/// before the snap, and nothing is kept after it).
#[derive(Clone, Debug, Default)]
pub struct TheoryFigures {
    kept: Vec<Kept>,
    /// The last frame before the window, so that the first fall is interpolated.
    before: Option<Kept>,
    /// The largest fall so far: once the fall is back below it, the free end has snapped
    /// and rebounds, and nothing more is kept.
    highest: f64,
    snapped: bool,
}

impl TheoryFigures {
    /// Takes an instant's comparisons (nothing happens for a scene without a fall).
    pub fn push(&mut self, time: f64, comparisons: &[Comparison]) {
        let Some(fall) = comparisons.iter().find(|c| c.quantity == Comparison::FALL) else {
            return;
        };
        let fall = fall.measured;
        if self.snapped || fall >= 0.999 || fall < self.highest - SNAP_REBOUND {
            self.snapped = true;
            return;
        }
        self.highest = self.highest.max(fall);
        let kept = Kept {
            time,
            fall,
            values: comparisons
                .iter()
                .filter(|c| c.quantity != Comparison::FALL)
                .map(|c| (c.quantity, c.measured, c.first_prediction()))
                .collect(),
        };
        let low = FOLD_FALLS[0] - FALL_WINDOW;
        let high = FOLD_FALLS[FOLD_FALLS.len() - 1] + FALL_WINDOW;
        if fall < low {
            self.before = Some(kept);
        } else if fall <= high || self.kept.last().is_some_and(|k| k.fall <= high) {
            // The first frame past the last window too, to interpolate the last fall.
            self.kept.push(kept);
        }
    }

    /// The theory at each of [`FOLD_FALLS`] the run reached.
    pub fn read(&self) -> Vec<TheoryAt> {
        let frames: Vec<&Kept> = self.before.iter().chain(&self.kept).collect();
        FOLD_FALLS
            .iter()
            .filter_map(|&target| {
                let pair = frames
                    .windows(2)
                    .find(|w| w[0].fall <= target && w[1].fall >= target)?;
                let (a, b) = (pair[0], pair[1]);
                let u = if b.fall > a.fall {
                    (target - a.fall) / (b.fall - a.fall)
                } else {
                    0.0
                };
                let lerp = |x: f64, y: f64| x + u * (y - x);
                let window: Vec<&&Kept> = frames
                    .iter()
                    .filter(|k| (k.fall - target).abs() <= FALL_WINDOW)
                    .collect();
                let momentum = a.values.iter().position(|v| v.0 == Comparison::MOMENTUM);
                let quantities = a
                    .values
                    .iter()
                    .zip(&b.values)
                    .enumerate()
                    .map(|(i, (&(quantity, ma, pa), &(_, mb, pb)))| {
                        let measured = lerp(ma, mb);
                        let predicted = pa.zip(pb).map(|(x, y)| lerp(x, y));
                        let (window_measured, window_predicted) =
                            match (quantity == Comparison::SUPPORT_TENSION, momentum) {
                                (true, Some(p)) => pulled(&window, p),
                                _ => (
                                    mean(&window, |k| Some(k.values[i].1)).unwrap_or(measured),
                                    mean(&window, |k| k.values[i].2),
                                ),
                            };
                        QuantityAt {
                            quantity,
                            measured,
                            predicted,
                            window_measured,
                            window_predicted,
                            relative_error: predicted.map(|p| measured / p - 1.0),
                            window_relative_error: window_predicted
                                .map(|p| window_measured / p - 1.0),
                        }
                    })
                    .collect();
                Some(TheoryAt {
                    fall: target,
                    time: lerp(a.time, b.time),
                    quantities,
                })
            })
            .collect()
    }
}

/// The mean over `window`'s frames of what `value` reads, if every frame has it.
fn mean(window: &[&&Kept], value: impl Fn(&Kept) -> Option<f64>) -> Option<f64> {
    let values: Option<Vec<f64>> = window.iter().map(|k| value(k)).collect();
    values
        .filter(|v| !v.is_empty())
        .map(|v| v.iter().sum::<f64>() / v.len() as f64)
}

/// The support's pull averaged over the time the window spans, measured and predicted, from
/// the downward momentum (its values at index `momentum`): the weight (1) less the momentum's
/// change over that time: the raw tension jumps each time a rod rounds the bend, and instants
/// sample those jumps by chance. Fed every step (`run::pipeline`), it does not depend
/// on the frames.
fn pulled(window: &[&&Kept], momentum: usize) -> (f64, Option<f64>) {
    let (Some(first), Some(last)) = (window.first(), window.last()) else {
        return (f64::NAN, None);
    };
    let span = last.time - first.time;
    if span <= 0.0 {
        return (f64::NAN, None);
    }
    let (m0, p0) = (first.values[momentum].1, first.values[momentum].2);
    let (m1, p1) = (last.values[momentum].1, last.values[momentum].2);
    let predicted = p0.zip(p1).map(|(p0, p1)| 1.0 - (p1 - p0) / span);
    (1.0 - (m1 - m0) / span, predicted)
}

/// How long the plotted pull is averaged over, in time units.
pub const PULL_WINDOW: f64 = 0.05;

/// The support's pull averaged over the last [`PULL_WINDOW`] of time, frame by frame, for
/// the plot: the weight less the change of the downward momentum over that time, measured
/// and as predicted (from the prediction of the momentum at the same frames).
#[derive(Clone, Debug, Default)]
pub struct PullWindow {
    /// (time, momentum measured, momentum predicted) of the frames since the window's start.
    recent: std::collections::VecDeque<(f64, f64, Option<f64>)>,
}

impl PullWindow {
    /// Takes a frame's comparisons; returns the pull over the window ending at it, once the
    /// frames span at least half a window (nothing for a scene without a momentum).
    pub fn push(&mut self, time: f64, comparisons: &[Comparison]) -> Option<Comparison> {
        let momentum = comparisons
            .iter()
            .find(|c| c.quantity == Comparison::MOMENTUM)?;
        self.recent
            .push_back((time, momentum.measured, momentum.first_prediction()));
        while self.recent.len() > 2 && self.recent[1].0 <= time - PULL_WINDOW {
            self.recent.pop_front();
        }
        let &(t0, m0, p0) = self.recent.front()?;
        let span = time - t0;
        if span < PULL_WINDOW / 2.0 {
            return None;
        }
        let pull = |now: f64, then: f64| 1.0 - (now - then) / span;
        Some(
            Comparison::new(Comparison::SUPPORT_PULL, pull(momentum.measured, m0)).predicted(
                "(1 + x)/2 + v²/4, averaged the same way",
                momentum
                    .first_prediction()
                    .zip(p0)
                    .map(|(p, p0)| pull(p, p0)),
            ),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(fall: f64, speed: f64) -> Vec<Comparison> {
        vec![
            Comparison::new(Comparison::FALL, fall),
            Comparison::new(Comparison::SPEED, speed).predicted("theory", Some(2.0 * speed)),
        ]
    }

    #[test]
    fn a_fall_between_two_frames_is_read_between_them() {
        let mut figures = TheoryFigures::default();
        // A fall growing as t, the speed as t too; frames every 0.1.
        for i in 0..12 {
            let t = i as f64 * 0.1;
            figures.push(t, &frame(t, t));
        }
        let read = figures.read();
        assert_eq!(read.len(), 3);
        for at in &read {
            assert!((at.time - at.fall).abs() < 1e-12);
            let speed = &at.quantities[0];
            assert!((speed.measured - at.fall).abs() < 1e-12);
            assert!((speed.relative_error.unwrap() + 0.5).abs() < 1e-12);
        }
    }

    #[test]
    fn the_pull_is_the_weight_less_the_momentum_gained_over_the_window() {
        let mut window = PullWindow::default();
        let mut last = None;
        // Momentum growing as 0.3 t: a steady pull of 0.7, measured and predicted.
        for i in 0..=20 {
            let t = i as f64 * 0.01;
            let frame = [
                Comparison::new(Comparison::MOMENTUM, 0.3 * t).predicted("theory", Some(0.3 * t))
            ];
            last = window.push(t, &frame);
            if t < PULL_WINDOW / 2.0 - 1e-12 {
                assert!(last.is_none(), "t = {t}");
            }
        }
        let pull = last.expect("a pull");
        assert!((pull.measured - 0.7).abs() < 1e-12);
        assert!((pull.first_prediction().unwrap() - 0.7).abs() < 1e-12);
        assert!(window.recent.len() <= 7);
    }

    #[test]
    fn a_scene_without_a_fall_reads_nothing_and_nothing_is_kept_after_the_snap() {
        let mut figures = TheoryFigures::default();
        figures.push(0.0, &[Comparison::new(Comparison::SPEED, 1.0)]);
        assert!(figures.read().is_empty());
        figures.push(0.0, &frame(0.0, 0.0));
        figures.push(1.0, &frame(1.0, 1.0));
        figures.push(2.0, &frame(0.5, 1.0));
        assert!(figures.read().is_empty());
    }
}
