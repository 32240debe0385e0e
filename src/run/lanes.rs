//! Several methods side by side (`--method A,B,…`): one simulation thread per method, and
//! the sink thread taking frame j of every method still running before frame j + 1 of any,
//! so the runs go in lockstep on the same frame times (each one's step brought onto a fixed
//! grid of shared instants, [`super::config::SHARED_FRAME_GRID`], that the frames fall on). It measures how far each string is
//! from the most accurate one's at every frame; a method that fails stops alone, and the
//! others go on.

use super::config::RunPlan;
use super::pipeline::{self, BATCH_FRAMES, CHANNEL_FRAMES, Delivery, Simulation};
use super::simulate::{Frame, Lane};
use super::sink::FrameSink;
use super::summary::Summary;
use crate::error::{ConfigError, Diverged};
use crate::model::geometry;
use crossbeam_channel::Receiver;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

/// How much simulated time of instants a paced run hands over at once.
const PACED_BATCH_TIME: f64 = 0.1;

/// What a method's thread sends: its frames, then how it ended.
enum Message {
    /// Boxed: a frame is large beside the end of a lane, and the channel holds either.
    Frame(Box<Frame>),
    /// The method's last frame has been sent; why it stopped early, if it did.
    Ended(Option<Diverged>),
}

/// Runs `plans` (one per method, the same scene and frame times) side by side, handing their
/// frames to `sink`, until each reaches the final time, diverges, or `stop` is set. Returns
/// each method's summary, in the order of `plans`; a sink that failed is in every one's
/// `recording_error`. `progress` hears the first frame of each instant, from the sink thread.
pub fn run<S: FrameSink>(
    plans: &[RunPlan],
    sink: &mut S,
    stop: &AtomicBool,
    progress: &(dyn Fn(&Frame) + Sync),
) -> Result<Vec<Summary>, ConfigError> {
    let mut methods = plans
        .iter()
        .map(RunPlan::build)
        .collect::<Result<Vec<_>, _>>()?;
    let mut shadows = plans
        .iter()
        .map(RunPlan::shadow)
        .collect::<Result<Vec<_>, _>>()?;
    let started = Instant::now();
    let (senders, receivers): (Vec<_>, Vec<_>) = plans
        .iter()
        .map(|_| crossbeam_channel::bounded::<Message>(CHANNEL_FRAMES))
        .unzip();
    let (lanes, delivered) = std::thread::scope(|scope| {
        let sink = &mut *sink;
        let sink_thread = scope.spawn(move || deliver(plans, sink, receivers, progress));
        let threads: Vec<_> = plans
            .iter()
            .zip(methods.iter_mut())
            .zip(shadows.iter_mut())
            .zip(senders)
            .map(|(((plan, method), shadow), tx)| {
                scope.spawn(move || {
                    let simulation = Simulation::of(plan, method.as_mut(), shadow.as_mut());
                    let send = |frame| tx.send(Message::Frame(Box::new(frame))).is_ok();
                    let lane =
                        pipeline::simulate_and_send(plan, simulation, send, stop, &|_| {}, started);
                    // A sink that has gone no longer listens; nothing is lost by not telling it.
                    let _ = tx.send(Message::Ended(lane.0.diverged.clone()));
                    lane
                })
            })
            .collect();
        let lanes: Vec<_> = threads
            .into_iter()
            .map(|t| t.join().unwrap_or_else(|p| std::panic::resume_unwind(p)))
            .collect();
        let delivered = sink_thread
            .join()
            .unwrap_or_else(|p| std::panic::resume_unwind(p));
        (lanes, delivered)
    });
    let ended = lanes.iter().map(|l| (l.0.time, l.0.steps));
    let (time, steps) = ended.fold((0.0, 0), |(t, n), (ti, ni)| (f64::max(t, ti), n.max(ni)));
    sink.end_run(time, steps);
    let (disagreement, recording_error) = match delivered {
        Ok(largest) => (largest, None),
        Err((largest, err)) => (largest, Some(err.to_string())),
    };
    Ok(plans
        .iter()
        .zip(lanes)
        .zip(disagreement)
        .map(|((plan, (outcome, tips, busy)), largest)| {
            let mut summary = Summary::new(
                plan,
                &outcome,
                tips,
                busy,
                started.elapsed(),
                recording_error.clone(),
            );
            summary.disagreement = largest;
            summary
        })
        .collect())
}

/// The largest disagreement of each method over the run (`None` for one that was always the
/// most accurate running), and how the sink failed, if it did.
type Delivered<E> = Result<Vec<Option<f64>>, (Vec<Option<f64>>, Delivery<E>)>;

/// The sink thread: takes frame j of every method still running, then frame j + 1; puts
/// each method's [`Lane`] into its frames; hands them over in batches (one instant at a
/// time when paced); tells the sink of a method that stopped early.
fn deliver<S: FrameSink>(
    plans: &[RunPlan],
    sink: &mut S,
    receivers: Vec<Receiver<Message>>,
    progress: &(dyn Fn(&Frame) + Sync),
) -> Delivered<S::Error> {
    let mut largest: Vec<Option<f64>> = vec![None; plans.len()];
    if let Err(err) = sink.begin_lanes(plans) {
        return Err((largest, Delivery::Begin(err)));
    }
    // Paced, about a tenth of a time unit of instants at a time: each send is a chunk per
    // entity and method, and a browser's viewer keeps up with fewer, larger chunks.
    let instants = match plans.first() {
        Some(p) if p.realtime.is_some() => (p.log_rate * PACED_BATCH_TIME).ceil().max(1.0) as usize,
        _ => BATCH_FRAMES,
    };
    let batch_frames = instants * plans.len();
    let mut live = vec![true; plans.len()];
    let mut batch: Vec<Frame> = Vec::with_capacity(batch_frames + plans.len());
    let mut instant: Vec<(usize, Frame)> = Vec::with_capacity(plans.len());
    while live.iter().any(|&l| l) {
        instant.clear();
        let mut stopped = Vec::new();
        for (i, rx) in receivers.iter().enumerate() {
            if !live[i] {
                continue;
            }
            match rx.recv() {
                Ok(Message::Frame(frame)) => instant.push((i, *frame)),
                Ok(Message::Ended(diverged)) => {
                    live[i] = false;
                    stopped.extend(diverged.map(|d| (i, d)));
                }
                Err(_) => live[i] = false,
            }
        }
        measure_disagreement(plans, &mut instant, &mut largest);
        if let Some((_, first)) = instant.first() {
            progress(first);
        }
        batch.extend(instant.drain(..).map(|(_, frame)| frame));
        if batch.len() >= batch_frames || !stopped.is_empty() || !live.iter().any(|&l| l) {
            if let Err(err) = sink.frames(&batch) {
                return Err((largest, Delivery::Frames(err)));
            }
            batch.clear();
        }
        for (i, why) in &stopped {
            if let Err(err) = sink.lane_ended(*i, why) {
                return Err((largest, Delivery::Frames(err)));
            }
        }
    }
    match sink.flush() {
        Ok(()) => Ok(largest),
        Err(err) => Err((largest, Delivery::Flush(err))),
    }
}

/// Marks each frame of one instant with its method and its largest distance, at equal arc
/// length, from the string of the most accurate method among them (`BY_ACCURACY`), and keeps
/// each method's largest.
fn measure_disagreement(
    plans: &[RunPlan],
    instant: &mut [(usize, Frame)],
    largest: &mut [Option<f64>],
) {
    let Some(best) = instant
        .iter()
        .min_by_key(|(i, _)| plans[*i].method.accuracy_rank())
        .map(|(i, _)| *i)
    else {
        return;
    };
    let Some(reference) = instant
        .iter()
        .find(|(i, _)| *i == best)
        .map(|(_, f)| (f.nodes.clone(), f.edges.clone()))
    else {
        return;
    };
    for (i, frame) in instant.iter_mut() {
        let disagreement = (*i != best).then(|| {
            geometry::largest_distance_of(
                &frame.nodes,
                frame.edges.as_deref(),
                &reference.0,
                reference.1.as_deref(),
            )
        });
        if let Some(d) = disagreement {
            largest[*i] = Some(largest[*i].map_or(d, |l: f64| l.max(d)));
        }
        frame.lane = Some(Lane {
            index: *i,
            method: plans[*i].method,
            disagreement,
        });
    }
}
