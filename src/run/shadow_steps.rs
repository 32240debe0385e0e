//! Where the live estimate's shadow gets its states: stepped on the run's own thread, just
//! when the run reaches each instant the two share ([`ShadowSteps::here`]), or ahead of it on
//! a core of its own, its states sent over a bounded channel in batches of [`BATCH`]
//! ([`ShadowSteps::ahead`]). The shadow never reads the run, so both give the same states,
//! bit for bit; only where the CPU is spent differs. A state sent ahead carries the shadow's
//! angles, not its nodes: the run draws nodes only at its frames, so a sine and cosine of
//! every rod at every step would be spent for nothing.

use super::trust::{ENERGY_BLOWUP, reference_energy};
use crate::error::Diverged;
use crate::methods::Method;
use crate::model::SupportNow;
use crate::model::geometry::{self, Point};
use crate::model::support::{into_the_room, point_in_the_room};
use crossbeam_channel::{Receiver, Sender};
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

/// How often, in time units, the shadow's energy is checked for a blow-up.
const ENERGY_CHECK_EVERY: f64 = 1e-3;

/// States the thread ahead sends at once. Sent one by one, each state read from a full
/// channel woke the waiting thread: at N = 1 000 the wake-ups of its 1 620 states took a
/// tenth to a fifth of the run's CPU (`docs/measurements.md`, "The fine rope: Newton's loops
/// by kind, the shadow's states in batches").
pub(super) const BATCH: usize = 8;

/// How many batches the thread ahead may have made that the run has not begun to read: it
/// waits there. Past the run's end it can have spent at most the rest of the batch being
/// read, this one and the one it was making: 23 steps of the shadow.
const AHEAD: usize = 1;

/// What the thread ahead sends at once: up to [`BATCH`] states in order, ending early at a
/// divergence.
type Batch = Vec<Result<State, Diverged>>;

/// The shadow's method and its blow-up watch.
pub(super) struct Stepper {
    method: Box<dyn Method>,
    /// The shadow's energy after the start-up, to see it blow up.
    energy_reference: f64,
    /// When the shadow's energy was last checked.
    energy_checked: f64,
}

impl Stepper {
    /// One step, then the energy about every [`ENERGY_CHECK_EVERY`] time units, as the run's
    /// own is watched: cheap against the steps between.
    fn step(&mut self) -> Result<(), Diverged> {
        self.method.step()?;
        if self.method.time() < self.energy_checked + ENERGY_CHECK_EVERY {
            return Ok(());
        }
        self.energy_checked = self.method.time();
        let energy = self.method.energy().total();
        if !energy.is_finite() || (energy - self.energy_reference).abs() > ENERGY_BLOWUP {
            return Err(Diverged {
                step: self.method.steps(),
                time: self.method.time(),
                reason: format!(
                    "the energy of the shadow at N = {} grew without bound: E = {energy:.3e}",
                    self.method.segments()
                ),
            });
        }
        Ok(())
    }

    /// The tip, in the room.
    fn tip(&self) -> Point {
        let m = &self.method;
        point_in_the_room(m.support(), m.tip())
    }

    /// The nodes (support … tip), in the room.
    fn nodes(&self, nodes: &mut Vec<Point>) {
        nodes_in_the_room(
            self.method.angles(),
            self.method.lengths(),
            self.method.support(),
            nodes,
        );
    }

    /// The state after its latest step, its angles copied into `angles` (a spare buffer).
    fn state(&self, mut angles: Vec<f64>) -> State {
        angles.clear();
        angles.extend_from_slice(self.method.angles());
        State {
            steps: self.method.steps(),
            tip: self.tip(),
            angles,
            support: self.method.support(),
        }
    }
}

/// The nodes (support … tip) of rods at `angles` of `lengths`, in the room where `support` is.
fn nodes_in_the_room(
    angles: &[f64],
    lengths: Option<&[f64]>,
    support: Option<SupportNow>,
    nodes: &mut Vec<Point>,
) {
    geometry::nodes_of(angles, lengths, nodes); // eqs. (14)–(15)
    into_the_room(support, nodes);
}

/// One state the thread ahead made: the shadow after `steps` steps, its tip, and what its
/// nodes are drawn from, should the run ask for them.
pub(super) struct State {
    steps: u64,
    tip: Point,
    angles: Vec<f64>,
    support: Option<SupportNow>,
}

/// The shadow's states, stepped here or ahead.
pub(super) enum ShadowSteps {
    Here(Box<Stepper>),
    Ahead {
        batches: Receiver<Batch>,
        /// The states of the batch being read, in order.
        unread: std::vec::IntoIter<Result<State, Diverged>>,
        /// Angle buffers the run has read, sent back to be filled again.
        spare: Sender<Vec<f64>>,
        /// The last state read.
        now: State,
        /// The shadow's rod lengths (fixed over a run), to draw its nodes from its angles.
        lengths: Option<Vec<f64>>,
        /// The thread's CPU nanoseconds so far.
        cpu_nanos: Arc<AtomicU64>,
    },
}

impl ShadowSteps {
    /// The shadow `method`, stepped on the run's thread.
    pub fn here(method: Box<dyn Method>) -> Self {
        Self::Here(Box::new(Stepper {
            energy_reference: reference_energy(method.as_ref()),
            method,
            energy_checked: f64::NEG_INFINITY,
        }))
    }

    /// The same, stepped ahead on a thread of its own; where the thread cannot start, here.
    pub fn ahead(self) -> Self {
        let Self::Here(mut stepper) = self else {
            return self;
        };
        let (send, batches) = crossbeam_channel::bounded::<Batch>(AHEAD);
        let (spare, recycled) = crossbeam_channel::unbounded::<Vec<f64>>();
        let cpu_nanos = Arc::new(AtomicU64::new(0));
        let counted = Arc::clone(&cpu_nanos);
        let first = stepper.state(Vec::new());
        let lengths = stepper.method.lengths().map(<[f64]>::to_vec);
        // The thread owns the shadow; the run reads what it sends, in order, until it drops
        // the receiver, which ends the thread at its next send.
        let spawned = std::thread::Builder::new()
            .name("rope-shadow".into())
            .spawn(move || {
                let cpu = cpu_time::ThreadTime::now();
                loop {
                    let mut batch = Batch::with_capacity(BATCH);
                    let mut lost = false;
                    while batch.len() < BATCH && !lost {
                        let made = stepper
                            .step()
                            .map(|()| stepper.state(recycled.try_recv().unwrap_or_default()));
                        lost = made.is_err();
                        batch.push(made);
                    }
                    let nanos = u64::try_from(cpu.elapsed().as_nanos()).unwrap_or(u64::MAX);
                    counted.store(nanos, Ordering::Relaxed);
                    if send.send(batch).is_err() || lost {
                        return;
                    }
                }
            });
        match spawned {
            Ok(_) => Self::Ahead {
                batches,
                unread: Batch::new().into_iter(),
                spare,
                now: first,
                lengths,
                cpu_nanos,
            },
            // (The closure, and the shadow in it, are gone with the failed spawn.)
            Err(err) => {
                let (send, batches) = crossbeam_channel::bounded(1);
                let _ = send.send(vec![Err(Diverged {
                    step: 0,
                    time: 0.0,
                    reason: format!("the shadow's thread could not start: {err}"),
                })]);
                Self::Ahead {
                    batches,
                    unread: Batch::new().into_iter(),
                    spare,
                    now: first,
                    lengths,
                    cpu_nanos,
                }
            }
        }
    }

    /// Brings the shadow to `target` steps (never back): `Err` why it stopped, if it did.
    pub fn advance_to(&mut self, target: u64) -> Result<(), Diverged> {
        match self {
            Self::Here(stepper) => {
                while stepper.method.steps() < target {
                    stepper.step()?;
                }
                Ok(())
            }
            Self::Ahead {
                batches,
                unread,
                spare,
                now,
                ..
            } => {
                while now.steps < target {
                    let Some(next) = unread.next() else {
                        *unread = batches
                            .recv()
                            .unwrap_or_else(|_| {
                                vec![Err(Diverged {
                                    step: now.steps + 1,
                                    time: f64::NAN,
                                    reason: "the shadow's thread stopped".to_owned(),
                                })]
                            })
                            .into_iter();
                        continue;
                    };
                    let next = next?;
                    let read = std::mem::replace(now, next);
                    let _ = spare.send(read.angles);
                }
                Ok(())
            }
        }
    }

    /// The shadow's tip now, in the room.
    pub fn tip(&self) -> Point {
        match self {
            Self::Here(stepper) => stepper.tip(),
            Self::Ahead { now, .. } => now.tip,
        }
    }

    /// The shadow's nodes now (support … tip), in the room, into `nodes`.
    pub fn nodes(&self, nodes: &mut Vec<Point>) {
        match self {
            Self::Here(stepper) => stepper.nodes(nodes),
            Self::Ahead { now, lengths, .. } => {
                nodes_in_the_room(&now.angles, lengths.as_deref(), now.support, nodes);
            }
        }
    }

    /// CPU seconds a thread of its own has spent on the shadow (none, stepped here: the run's
    /// thread counts them).
    pub fn own_thread_seconds(&self) -> f64 {
        match self {
            Self::Here(_) => 0.0,
            Self::Ahead { cpu_nanos, .. } => cpu_nanos.load(Ordering::Relaxed) as f64 * 1e-9,
        }
    }
}
