//! Writes frames to a Rerun recording stream: the rope coloured by tension, the tension
//! profile, energy and tip time series, and the run's parameters. Knows nothing of the
//! equations: it draws what a [`Frame`] holds.

use super::entities::{SERIES, log10_abs};
use super::entities::{SIM_TIME, STEP, path};
use super::error::RecordingError;
use super::lane_log::{LaneLog, style_of};
use super::live::{HistoryRates, Keeping, LivePicture};
use super::shapes::{
    ROPE_RADIUS, SharedShapes, ThenShape, advance_trail, send_moving_support, send_profiles,
    send_rope, send_tips, send_trails, then_label, xy,
};
use super::styling;
use crate::error::Diverged;
use crate::run::{Frame, FrameSink, RunPlan};
use rerun::RecordingStream;
use std::time::{Duration, Instant};

/// How long the end of a run waits for the recording's destinations to take the last data.
/// Longer than a viewer's own cap (`viewer_sinks::FLUSH_CAP`), so that a viewer that cannot
/// take the data is reported by its link, with its own reason.
const FLUSH_TIMEOUT: Duration = Duration::from_secs(5);

/// A paced run sends each frame's shapes at once, but gathers the time series of up to this
/// many frames (or [`SERIES_WAIT`]) into one chunk per series: each chunk carries its own
/// schema, about 1.5 kB, and sending seven series a frame made a paced stream five times
/// the size of a batched one.
const SERIES_FRAMES: usize = 6;
/// How long the time series may wait to be sent: the plots refresh at least this often.
const SERIES_WAIT: Duration = Duration::from_millis(100);
/// The same two side by side, where a chunk per series, lane and tenth of a second made the
/// series a third of what a browser keeps (several methods, five series each): the plots
/// refresh once a second.
const SIDE_BY_SIDE_SERIES_FRAMES: usize = 25;
const SIDE_BY_SIDE_SERIES_WAIT: Duration = Duration::from_secs(1);

/// The time columns of rows at `sim_time` seconds and `step` steps, both timelines.
fn timelines(
    sim_time: impl IntoIterator<Item = f64>,
    step: impl IntoIterator<Item = i64>,
) -> [rerun::TimeColumn; 2] {
    [
        rerun::TimeColumn::new_duration_secs(SIM_TIME, sim_time),
        rerun::TimeColumn::new_sequence(STEP, step),
    ]
}

/// Streams frames of runs into a recording. Runs follow one another on the timelines: each
/// starts where the one before it ended (`--loop`), so one recording holds them all.
pub struct RopeLogger {
    /// The timelines: every frame, or the history beside a live picture.
    rec: RecordingStream,
    keeping: Keeping,
    /// The picture that replaces itself, for viewers of a run that never ends.
    live: Option<LivePicture>,
    /// Where on `sim_time` the history keeps its next shape of the rope.
    next_shape: f64,
    /// The history's shapes not yet sent.
    then: Vec<ThenShape>,
    /// Where on `sim_time` the history next sends what it gathered, and every how many
    /// time units it sends: [`FIRST_SEND_UNITS`] at first, so that the plots fill soon
    /// after a viewer opens, doubling up to [`HISTORY_SEND_UNITS`].
    next_send: f64,
    send_every: f64,
    /// What is running: the caption over the live rope.
    headline: String,
    /// One per method of the current run.
    lanes: Vec<LaneLog>,
    series_sent: Instant,
    /// Where the current run's t = 0 and step 0 lie on the timelines.
    time_offset: f64,
    step_offset: u64,
    /// The current run's `--tolerance`, drawn beside the estimate.
    tolerance: Option<f64>,
    /// Added to every run's parameters.
    parameters_note: Option<String>,
    /// Frames to gather before logging them (0: log each batch as it comes).
    gather: usize,
    pending: Vec<Frame>,
}

impl RopeLogger {
    /// A recording of every frame: logs what never changes (the support, the colour scale,
    /// and the series' names and colours).
    pub fn new(rec: RecordingStream) -> rerun::RecordingStreamResult<Self> {
        Self::keeping(rec, Keeping::Everything, None)
    }

    /// A recording of every frame that nobody watches as it grows (a `--save` file beside
    /// viewers that get a live picture): frames are gathered [`FILE_GATHER`] at a time, even
    /// when paced to the wall clock, so that the file holds a chunk per entity and
    /// [`FILE_GATHER`] frames rather than per frame. Rerun's file sink keeps an index entry
    /// (about 400 bytes) per chunk in memory until it writes the footer: per frame, an
    /// endless run's process grew by 0.4 MB a second.
    pub fn file_beside_viewers(rec: RecordingStream) -> rerun::RecordingStreamResult<Self> {
        let mut logger = Self::new(rec)?;
        logger.gather = FILE_GATHER;
        Ok(logger)
    }

    /// A live picture into `live` and a history at `rates` into `history`: two streams of
    /// one recording, for viewers of a run that never ends (see [`super::live`]).
    pub fn live(
        history: RecordingStream,
        live: RecordingStream,
        rates: HistoryRates,
    ) -> rerun::RecordingStreamResult<Self> {
        let logger = Self::keeping(
            history,
            Keeping::History(rates),
            Some(LivePicture::new(live)),
        )?;
        styling::log_then_styling(&logger.rec)?;
        Ok(logger)
    }

    fn keeping(
        rec: RecordingStream,
        keeping: Keeping,
        live: Option<LivePicture>,
    ) -> rerun::RecordingStreamResult<Self> {
        rec.log_static(
            path::SUPPORT,
            &rerun::Points2D::new([[0.0f32, 0.0]])
                .with_radii([0.02])
                .with_colors([rerun::Color::from_rgb(90, 90, 90)])
                .with_labels(["support"]),
        )?;
        // The caption's text is the run's headline, logged as each run begins.
        rec.log_static(
            path::CAPTION,
            &rerun::Points2D::new([[0.0f32, -0.25]])
                .with_radii([0.001])
                .with_colors([rerun::Color::from_rgb(140, 140, 140)])
                .with_show_labels(true),
        )?;
        styling::log_scale(&rec, false)?;
        styling::log_profile_axes(&rec)?;
        // Styling that never changes is logged once; frames carry only what moves.
        rec.log_static(
            path::SEGMENTS,
            &rerun::LineStrips2D::update_fields().with_radii([ROPE_RADIUS]),
        )?;
        rec.log_static(
            path::TIP,
            &rerun::Points2D::update_fields()
                .with_radii([0.015])
                .with_colors([rerun::Color::from_rgb(20, 20, 20)]),
        )?;
        rec.log_static(
            path::TRAIL,
            &rerun::LineStrips2D::update_fields()
                .with_radii([0.002])
                .with_colors([rerun::Color::from_unmultiplied_rgba(40, 40, 40, 110)]),
        )?;
        rec.log_static(
            path::PROFILE,
            &rerun::LineStrips2D::update_fields()
                .with_radii([0.008])
                .with_colors([rerun::Color::from_rgb(230, 150, 0)]),
        )?;
        Ok(Self {
            rec,
            keeping,
            live,
            next_shape: 0.0,
            then: Vec::new(),
            next_send: FIRST_SEND_UNITS,
            send_every: FIRST_SEND_UNITS,
            headline: String::new(),
            lanes: vec![LaneLog::alone(None, keeping)],
            series_sent: Instant::now(),
            time_offset: 0.0,
            step_offset: 0,
            tolerance: None,
            parameters_note: None,
            gather: 0,
            pending: Vec::new(),
        })
    }

    /// The `sim_time` and `step` columns of `frames`, placed after the runs before.
    fn frame_times(&self, frames: &[&Frame]) -> Vec<rerun::TimeColumn> {
        let (time_offset, step_offset) = (self.time_offset, self.step_offset);
        timelines(
            frames.iter().map(|f| time_offset + f.time),
            frames.iter().map(|f| (step_offset + f.step) as i64),
        )
        .into()
    }

    /// Logs a batch of frames, in order: on the `sim_time` and `step` timelines every frame,
    /// or the history's share of them, sent as columns (one chunk per entity for the whole
    /// batch, far cheaper than a log call per frame and entity); and the last one as the
    /// live picture, when one is due.
    pub fn log_frames(&mut self, frames: &[Frame]) -> rerun::RecordingStreamResult<()> {
        if self.lanes.len() > 1 {
            self.log_shared_shapes(frames)?;
        } else {
            self.log_shapes(frames)?;
        }
        for lane in 0..self.lanes.len() {
            let mine: Vec<&Frame> = frames.iter().filter(|f| self.lanes[lane].owns(f)).collect();
            if mine.is_empty() {
                continue;
            }
            self.log_tolerance_passed(lane, &mine)?;
            self.gather_series(lane, &mine);
        }
        let gathered: usize = self.lanes.iter().map(|l| l.series.len()).sum();
        let (most, wait) = match self.lanes.len() {
            1 => (SERIES_FRAMES, SERIES_WAIT),
            lanes => (SIDE_BY_SIDE_SERIES_FRAMES * lanes, SIDE_BY_SIDE_SERIES_WAIT),
        };
        let due = match self.keeping {
            Keeping::Everything => gathered >= most || self.series_sent.elapsed() >= wait,
            // A history's rows are few: gathered over [`HISTORY_SEND_UNITS`] of simulated
            // time, they make a few large chunks, the same whatever the run's speed.
            Keeping::History(_) => match frames.last().map(|f| self.time_offset + f.time) {
                Some(t) if t >= self.next_send => {
                    let every = self.send_every;
                    self.next_send = ((t / every + 1e-9).floor() + 1.0) * every;
                    self.send_every = (2.0 * every).min(HISTORY_SEND_UNITS);
                    true
                }
                _ => false,
            },
        };
        if due {
            self.send_series()?;
        }
        Ok(())
    }

    /// Which of `times` (on the timeline) the history keeps the rope's shape at: the first at
    /// or past each multiple of its interval.
    fn kept_shapes(&mut self, times: impl IntoIterator<Item = f64>) -> Vec<usize> {
        let Keeping::History(rates) = self.keeping else {
            return Vec::new();
        };
        let interval = rates.shape_interval();
        let mut kept = Vec::new();
        for (i, t) in times.into_iter().enumerate() {
            if t >= self.next_shape - 1e-9 * interval {
                kept.push(i);
                self.next_shape = ((t / interval + 1e-9).floor() + 1.0) * interval;
            }
        }
        kept
    }

    /// A run of one method: its rope, tip, trail and tension profile at every frame, or
    /// the history's shapes and the live picture.
    fn log_shapes(&mut self, frames: &[Frame]) -> rerun::RecordingStreamResult<()> {
        let frames: Vec<&Frame> = frames.iter().collect();
        let Some(&last) = frames.last() else {
            return Ok(());
        };
        let tips: Vec<[f32; 2]> = frames.iter().map(|f| xy(&f.tip())).collect();
        let everything = self.keeping == Keeping::Everything;
        let trails = advance_trail(&mut self.lanes[0].trail, &tips, everything);
        if everything {
            let times = self.frame_times(&frames);
            send_rope(&self.rec, path::SEGMENTS, &frames, times.clone())?;
            send_tips(&self.rec, path::TIP, tips, times.clone())?;
            send_moving_support(&self.rec, &frames, times.clone())?;
            send_trails(&self.rec, path::TRAIL, trails, times.clone())?;
            send_profiles(&self.rec, path::PROFILE, &frames, times)?;
        } else {
            let offset = self.time_offset;
            let kept = self.kept_shapes(frames.iter().map(|f| offset + f.time));
            self.then.extend(kept.into_iter().map(|i| ThenShape {
                time: offset + frames[i].time,
                step: (self.step_offset + frames[i].step) as i64,
                frames: vec![frames[i].clone()],
            }));
        }
        if self.live.as_mut().is_some_and(LivePicture::due)
            && let Some(live) = &self.live
        {
            let trail = self.lanes[0].trail.iter().copied().collect();
            let rec = &live.rec;
            send_rope(rec, path::SEGMENTS, &[last], Vec::new())?;
            send_tips(rec, path::TIP, vec![xy(&last.tip())], Vec::new())?;
            send_moving_support(rec, &[last], Vec::new())?;
            send_trails(rec, path::TRAIL, vec![trail], Vec::new())?;
            send_profiles(rec, path::PROFILE, &[last], Vec::new())?;
            self.log_live_caption(self.time_offset + last.time)?;
        }
        Ok(())
    }

    /// The live caption: what is running, and the time it has reached.
    fn log_live_caption(&mut self, time: f64) -> rerun::RecordingStreamResult<()> {
        let Some(live) = &mut self.live else {
            return Ok(());
        };
        if !live.caption_due() {
            return Ok(());
        }
        live.rec.log_static(
            path::CAPTION,
            &rerun::Points2D::update_fields()
                .with_labels([format!("{} · live, t = {time:.1}", self.headline)]),
        )
    }

    /// Several methods side by side: each instant's ropes, tips and tension profiles as one
    /// row of three entities shared by the methods (a method that stopped is no longer in
    /// them). A browser's viewer keeps every chunk it is sent, each with its own schema and
    /// index: three entities an instant instead of three per method, and the ropes in
    /// [`SHADE`]s of tension (a strip per run of one shade, about half the points), make
    /// what it keeps grow about a quarter as fast. A history keeps its share of the
    /// instants under `then/` (no profiles), and the live picture the last one.
    fn log_shared_shapes(&mut self, frames: &[Frame]) -> rerun::RecordingStreamResult<()> {
        // The frames of one instant come together, in the methods' order.
        let mut instants: Vec<Vec<&Frame>> = Vec::new();
        let mut last_lane = None;
        for f in frames {
            let lane = f.lane.map(|l| l.index);
            match instants.last_mut() {
                Some(instant) if lane > last_lane => instant.push(f),
                _ => instants.push(vec![f]),
            }
            last_lane = lane;
        }
        let offset = self.time_offset;
        let step_offset = self.step_offset;
        let kept = self.kept_shapes(instants.iter().map(|i| offset + i[0].time));
        self.then.extend(kept.into_iter().map(|i| ThenShape {
            time: offset + instants[i][0].time,
            step: (step_offset + instants[i][0].step) as i64,
            frames: instants[i].iter().map(|&f| f.clone()).collect(),
        }));
        let live_due = self.live.as_mut().is_some_and(LivePicture::due);
        let lane_of = |f: &Frame| style_of(&self.lanes, f);
        let times = |instants: &[Vec<&Frame>]| {
            vec![rerun::TimeColumn::new_duration_secs(
                SIM_TIME,
                instants.iter().map(|i| offset + i[0].time),
            )]
        };
        let shared = [path::SEGMENTS, path::TIPS, path::PROFILES];
        if self.keeping == Keeping::Everything && !instants.is_empty() {
            SharedShapes::of(&instants, lane_of, true).send(&self.rec, shared, times(&instants))?;
        }
        if live_due && let (Some(live), Some(now)) = (&self.live, instants.last()) {
            // Static: one instant, which replaces the one before.
            SharedShapes::of(std::slice::from_ref(now), lane_of, true).send(
                &live.rec,
                shared,
                Vec::new(),
            )?;
            self.log_live_caption(offset + now[0].time)?;
        }
        Ok(())
    }

    /// The frame at which the estimate passed the tolerance, if it is among `frames`: a
    /// marker on the error plot and a warning in the events.
    fn log_tolerance_passed(
        &self,
        lane: usize,
        frames: &[&Frame],
    ) -> rerun::RecordingStreamResult<()> {
        let lane = &self.lanes[lane];
        for passed in frames.iter().filter_map(|f| f.tolerance_exceeded) {
            let tip = passed.estimate;
            let eps = self.tolerance.unwrap_or(f64::NAN);
            let times = timelines(
                [self.time_offset + passed.time],
                [(self.step_offset + passed.step) as i64],
            );
            for (entity, value) in [
                (path::TOLERANCE_PASSED, tip),
                (path::LOG_TOLERANCE_PASSED, log10_abs(tip)),
            ] {
                self.rec.send_columns(
                    lane.at(entity),
                    times.clone(),
                    rerun::Scalars::new([value]).columns_of_unit_batches()?,
                )?;
            }
            self.rec.send_columns(
                path::EVENTS,
                times,
                rerun::TextLog::update_fields()
                    .with_text(format!(
                        "the estimated tip error {tip:.1e} passed the tolerance {eps:.1e} at t = {:.4}",
                        passed.time
                    ))
                    .with_level(rerun::TextLogLevel::WARN)
                    .columns_of_unit_batches()?,
            )?;
        }
        Ok(())
    }

    /// Sends the history's shapes of the rope gathered so far.
    fn send_then(&mut self) -> rerun::RecordingStreamResult<()> {
        if self.then.is_empty() {
            return Ok(());
        }
        let then = std::mem::take(&mut self.then);
        let times = timelines(then.iter().map(|t| t.time), then.iter().map(|t| t.step));
        let instants: Vec<Vec<&Frame>> = then.iter().map(|t| t.frames.iter().collect()).collect();
        let side_by_side = self.lanes.len() > 1;
        let shapes = SharedShapes::of(
            &instants,
            |f: &Frame| style_of(&self.lanes, f),
            side_by_side,
        );
        if side_by_side {
            return shapes.send(
                &self.rec,
                [path::THEN_SEGMENTS, path::THEN_TIPS, ""],
                times.into(),
            );
        }
        self.rec.send_columns(
            path::THEN_SEGMENTS,
            times.clone(),
            rerun::LineStrips2D::update_fields()
                .with_strips(shapes.ropes)
                .with_colors(shapes.rope_colours)
                .columns(shapes.rope_lengths)?,
        )?;
        self.rec.send_columns(
            path::THEN_TIP,
            times,
            rerun::Points2D::update_fields()
                .with_positions(shapes.tips)
                .with_labels(then.iter().map(|t| then_label(t.time)))
                .columns_of_unit_batches()?,
        )
    }

    /// Adds the frames' time series to those of their lane not yet sent.
    fn gather_series(&mut self, lane: usize, frames: &[&Frame]) {
        let (time_offset, step_offset) = (self.time_offset, self.step_offset);
        let lane = &mut self.lanes[lane];
        for f in frames {
            // Side by side a frame's marks (the tolerance passed) are not series: none is lost.
            if lane.frames_seen.is_multiple_of(lane.series_stride) {
                lane.series.push((
                    time_offset + f.time,
                    (step_offset + f.step) as i64,
                    SERIES.map(|(_, _, _, value)| value(f)),
                ));
            }
            lane.frames_seen += 1;
        }
    }

    /// Sends the time series gathered so far, one chunk per series and lane.
    pub fn send_series(&mut self) -> rerun::RecordingStreamResult<()> {
        self.series_sent = Instant::now();
        self.send_then()?;
        for lane in &mut self.lanes {
            send_lane_series(&self.rec, lane, self.tolerance)?;
        }
        Ok(())
    }
}

/// The [`LaneLog::styled`] bit of the tolerance's styling.
const TOLERANCE_STYLED: u64 = 1 << 63;

/// How series `i` of [`SERIES`] is drawn in `lane`: alone, in its own name and colour; one
/// method of several side by side, in the method's colour, named by it.
fn series_style(lane: &LaneLog, i: usize) -> rerun::SeriesLines {
    let (entity, name, [r, g, b], _) = SERIES[i];
    let (name, colour) = match lane.index {
        None => (name.to_owned(), rerun::Color::from_rgb(r, g, b)),
        Some(_) if entity.starts_with("energy/") => (format!("{} {name}", lane.name), lane.colour),
        Some(_) => (lane.name.to_owned(), lane.colour),
    };
    rerun::SeriesLines::new()
        .with_names([name])
        .with_colors([colour])
}

/// The tolerance's line and the points where the estimate passed it, in red.
fn log_tolerance_style(rec: &RecordingStream) -> rerun::RecordingStreamResult<()> {
    for (tolerance, passed, name) in [
        (path::TOLERANCE, path::TOLERANCE_PASSED, "tolerance"),
        (
            path::LOG_TOLERANCE,
            path::LOG_TOLERANCE_PASSED,
            "log₁₀ tolerance",
        ),
    ] {
        rec.log_static(
            tolerance,
            &rerun::SeriesLines::new()
                .with_names([name])
                .with_colors([rerun::Color::from_rgb(200, 40, 40)]),
        )?;
        rec.log_static(
            passed,
            &rerun::SeriesPoints::new()
                .with_names(["passed the tolerance"])
                .with_colors([rerun::Color::from_rgb(200, 40, 40)])
                .with_marker_sizes([6.0]),
        )?;
    }
    Ok(())
}

/// Sends one lane's gathered time series, one chunk per series.
fn send_lane_series(
    rec: &RecordingStream,
    lane: &mut LaneLog,
    tolerance: Option<f64>,
) -> rerun::RecordingStreamResult<()> {
    {
        if lane.series.is_empty() {
            return Ok(());
        }
        let rows = &lane.series;
        for (i, (entity, ..)) in SERIES.iter().enumerate() {
            if !lane.sends(entity) {
                continue;
            }
            // A value a frame does not have (NaN) is not sent: a series a method does not
            // have is not sent at all.
            let kept = || rows.iter().filter(move |r| !r.2[i].is_nan());
            if kept().next().is_none() {
                continue;
            }
            if lane.styled & (1 << i) == 0 {
                rec.log_static(lane.at(entity), &series_style(lane, i))?;
                lane.styled |= 1 << i;
            }
            rec.send_columns(
                lane.at(entity),
                timelines(kept().map(|r| r.0), kept().map(|r| r.1)),
                rerun::Scalars::new(kept().map(|r| r.2[i])).columns_of_unit_batches()?,
            )?;
        }
        if let Some(eps) = tolerance {
            if lane.styled & TOLERANCE_STYLED == 0 {
                log_tolerance_style(rec)?;
                lane.styled |= TOLERANCE_STYLED;
            }
            for (entity, value) in [
                (path::TOLERANCE, eps),
                (path::LOG_TOLERANCE, log10_abs(eps)),
            ] {
                rec.send_columns(
                    lane.at(entity),
                    timelines(rows.iter().map(|r| r.0), rows.iter().map(|r| r.1)),
                    rerun::Scalars::new(rows.iter().map(|_| value)).columns_of_unit_batches()?,
                )?;
            }
        }
        lane.series.clear();
        Ok(())
    }
}

impl RopeLogger {
    /// The sweep of the shaking frequency so far: each run's Ω and the free end's largest
    /// swing, for a support of `amplitude` ([`super::sweep_view`]).
    pub fn log_sweep(
        &self,
        amplitude: f64,
        points: &[crate::run::shake_figures::SweepPoint],
    ) -> rerun::RecordingStreamResult<()> {
        super::sweep_view::log_sweep(&self.rec, amplitude, points)
    }

    /// What is running, where the run starts: the caption over the rope, and the parameters.
    fn log_run_text(&mut self, headline: String, markdown: String) -> Result<(), RecordingError> {
        let (time, step) = (self.time_offset, self.step_offset as i64);
        let times = || timelines([time], [step]);
        // A history keeps a shape where each run starts.
        self.next_shape = time;
        self.headline.clone_from(&headline);
        if let Some(live) = &mut self.live {
            live.caption_now();
            self.log_live_caption(time)?;
        } else {
            self.rec.send_columns(
                path::CAPTION,
                times(),
                rerun::Points2D::update_fields()
                    .with_labels([headline])
                    .columns_of_unit_batches()?,
            )?;
        }
        let markdown = match &self.parameters_note {
            Some(note) => format!("{markdown}\n\n{note}"),
            None => markdown,
        };
        self.rec.send_columns(
            path::PARAMETERS,
            times(),
            rerun::TextDocument::update_fields()
                .with_text(markdown)
                .with_media_type(rerun::MediaType::markdown())
                .columns_of_unit_batches()?,
        )?;
        Ok(())
    }

    /// Logs the frames gathered so far (see [`RopeLogger::file_beside_viewers`]).
    fn log_pending(&mut self) -> rerun::RecordingStreamResult<()> {
        if self.pending.is_empty() {
            return Ok(());
        }
        let pending = std::mem::take(&mut self.pending);
        self.log_frames(&pending)?;
        self.pending = pending;
        self.pending.clear();
        Ok(())
    }

    /// Text added to every run's parameters (markdown): what the history costs a viewer.
    pub fn note_in_parameters(&mut self, note: String) {
        self.parameters_note = Some(note);
    }
}

/// Time units of simulated time over which a history gathers its rows and shapes before
/// sending them: a chunk per series and lane carries about 1.2 kB besides its rows, so a
/// history sends a few large ones, at the same bytes per time unit whatever the run's speed.
pub const HISTORY_SEND_UNITS: f64 = 20.0;

/// Frames a file beside viewers gathers before logging them: two seconds of a paced run.
pub const FILE_GATHER: usize = 120;

/// Time units before a history first sends what it gathered (then 4, 8, 16, 20, …).
pub const FIRST_SEND_UNITS: f64 = 2.0;

/// A recording of runs, one after another on the timelines: each starts where the one
/// before it ended (`--loop`), with its parameters logged there and a fresh trail.
impl FrameSink for RopeLogger {
    type Error = RecordingError;

    fn begin_run(&mut self, plan: &RunPlan) -> Result<(), RecordingError> {
        // What was gathered belongs to the run before, and to its tolerance.
        self.log_pending()?;
        self.send_series()?;
        self.lanes = vec![LaneLog::alone(Some(plan), self.keeping)];
        self.tolerance = plan.tolerance;
        styling::log_support_track(&self.rec, plan.scene.support())?;
        self.log_run_text(plan.headline(), plan.markdown())
    }

    fn begin_lanes(&mut self, plans: &[RunPlan]) -> Result<(), RecordingError> {
        self.log_pending()?;
        self.send_series()?;
        self.tolerance = None; // (--tolerance chooses one method: never side by side)
        self.lanes = plans
            .iter()
            .enumerate()
            .map(|(i, p)| LaneLog::of(i, p, self.keeping))
            .collect();
        // The shared shapes' styling; their colours come with each instant, and the legend
        // names them (a label at each tip piled up where the tips met).
        self.rec.log_static(
            path::TIPS,
            &rerun::Points2D::update_fields().with_radii([0.018]),
        )?;
        styling::log_scale(&self.rec, true)?;
        self.rec.log_static(
            path::PROFILES,
            &rerun::LineStrips2D::update_fields().with_radii([0.008]),
        )?;
        let names: Vec<&str> = self.lanes.iter().map(|l| l.name).collect();
        // The methods' colours, a row each, upward from above the caption (which is at
        // y = −0.25), however many there are.
        let rows = plans.len();
        self.rec.log_static(
            path::LEGEND,
            &rerun::Points2D::new(
                (0..rows).map(|i| [-0.85f32, -0.45 - 0.1 * (rows - 1 - i) as f32]),
            )
            .with_radii([0.025])
            .with_colors(self.lanes.iter().map(|l| l.colour))
            .with_labels(names.iter().map(|n| n.to_string()))
            .with_show_labels(true),
        )?;
        let headline = match plans.first() {
            Some(p) => format!(
                "{} side by side, {}, N = {}",
                names.join(", "),
                p.scene,
                p.segments
            ),
            None => String::new(),
        };
        let markdown: Vec<String> = plans.iter().map(RunPlan::markdown).collect();
        self.log_run_text(headline, markdown.join("\n\n---\n\n"))
    }

    /// The events say when and why a method stopped (its rope, tip and profile are no longer
    /// in the instants after its last frame).
    fn lane_ended(&mut self, lane: usize, why: &Diverged) -> Result<(), RecordingError> {
        self.log_pending()?;
        self.send_series()?;
        let Some(lane) = self.lanes.iter().find(|l| l.index == Some(lane)) else {
            return Ok(());
        };
        let method = lane.name;
        self.rec.send_columns(
            path::EVENTS,
            timelines(
                [self.time_offset + why.time],
                [(self.step_offset + why.step) as i64],
            ),
            rerun::TextLog::update_fields()
                .with_text(format!(
                    "{method} diverged at t = {:.3} ({})",
                    why.time, why.reason
                ))
                .with_level(rerun::TextLogLevel::WARN)
                .columns_of_unit_batches()?,
        )?;
        // Its plots stop here: a clear breaks each line, which would otherwise run straight
        // on to where the method starts again (the next pass of a loop).
        for (entity, ..) in SERIES.into_iter().filter(|(e, ..)| lane.sends(e)) {
            self.rec.send_columns(
                lane.at(entity),
                timelines(
                    [self.time_offset + why.time],
                    [(self.step_offset + why.step) as i64],
                ),
                rerun::Clear::flat().columns_of_unit_batches()?,
            )?;
        }
        Ok(())
    }

    fn frames(&mut self, frames: &[Frame]) -> Result<(), RecordingError> {
        if self.gather == 0 {
            return Ok(self.log_frames(frames)?);
        }
        self.pending.extend_from_slice(frames);
        if self.pending.len() >= self.gather {
            self.log_pending()?;
        }
        Ok(())
    }

    fn flush(&mut self) -> Result<(), RecordingError> {
        self.log_pending()?;
        self.send_series()?;
        Ok(self.rec.flush_with_timeout(FLUSH_TIMEOUT)?)
    }

    /// Time series still gathered keep their own times.
    fn end_run(&mut self, time: f64, steps: u64) {
        self.time_offset += time;
        self.step_offset += steps;
    }
}
