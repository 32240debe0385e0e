//! Writes frames to a Rerun recording stream: the rope coloured by tension, the tension
//! profile, energy and tip time series, and the run's parameters. Knows nothing of the
//! equations: it draws what a [`Frame`] holds.

use super::colour::{SHADE, shaded_strips, tension_colour};
use super::entities::{SERIES, SIDE_BY_SIDE, log10_abs};
use super::entities::{SIM_TIME, STEP, path};
use super::error::RecordingError;
use crate::error::Diverged;
use crate::model::Point;
use crate::run::{Frame, FrameSink, RunPlan};
use rerun::RecordingStream;
use std::collections::VecDeque;
use std::time::{Duration, Instant};

/// How long the end of a run waits for the recording's destinations to take the last data.
/// Longer than a viewer's own cap (`viewer_sinks::FLUSH_CAP`), so that a viewer that cannot
/// take the data is reported by its link, with its own reason.
const FLUSH_TIMEOUT: Duration = Duration::from_secs(5);

/// Room for the time series of a batch of frames without reallocating.
const BATCH_SERIES_CAPACITY: usize = 32;

/// The time series of one frame, one value per [`SERIES`] entry.
type SeriesRow = (f64, i64, [f64; SERIES.len()]);

/// What the logger keeps for one method's frames: where its entities go, its trail, and its
/// time series not yet sent. A run of one method has one, with the plain entity paths.
struct LaneLog {
    /// Where the method stands among several side by side; `None` in a run of one method.
    index: Option<usize>,
    /// The method's name side by side.
    name: &'static str,
    /// The method's colour side by side (its finest shade on the study's charts).
    colour: rerun::Color,
    /// What its entity paths end with: "" alone, "/{method}" side by side.
    suffix: String,
    trail: VecDeque<[f32; 2]>,
    series: Vec<SeriesRow>,
    /// Every how many frames a row of time series is kept: 1 alone; side by side, enough to
    /// keep [`SIDE_BY_SIDE_SERIES_RATE`] rows per time unit (the plots redraw their whole
    /// history every frame, and a browser on a small machine could not keep up with more).
    series_stride: u64,
    /// Frames of this lane seen so far.
    frames_seen: u64,
}

/// Rows of time series per time unit each of several methods side by side sends at most.
const SIDE_BY_SIDE_SERIES_RATE: f64 = 10.0;

impl LaneLog {
    /// The one lane of a run of one method.
    fn alone() -> Self {
        Self::new(None, "", [0, 0, 0], 1)
    }

    /// The lane of the method at `index` among several side by side.
    fn of(index: usize, plan: &RunPlan) -> Self {
        let stride = (plan.log_rate / SIDE_BY_SIDE_SERIES_RATE).ceil().max(1.0) as u64;
        Self::new(
            Some(index),
            plan.method.name(),
            plan.method.descriptor().colours.1,
            stride,
        )
    }

    fn new(
        index: Option<usize>,
        name: &'static str,
        [r, g, b]: [u8; 3],
        series_stride: u64,
    ) -> Self {
        Self {
            index,
            name,
            colour: rerun::Color::from_rgb(r, g, b),
            suffix: index.map_or(String::new(), |_| format!("/{name}")),
            trail: VecDeque::with_capacity(TRAIL_FRAMES),
            series: Vec::with_capacity(BATCH_SERIES_CAPACITY),
            series_stride,
            frames_seen: 0,
        }
    }

    /// `entity`'s path for this lane.
    fn at(&self, entity: &str) -> String {
        format!("{entity}{}", self.suffix)
    }

    /// Whether this lane sends the time series of `entity`.
    fn sends(&self, entity: &str) -> bool {
        self.index.is_none() || SIDE_BY_SIDE.contains(&entity)
    }

    /// Whether `frame` is of this lane.
    fn owns(&self, frame: &Frame) -> bool {
        frame.lane.map(|l| l.index) == self.index
    }
}

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

/// How many frames of the tip's path the trail keeps.
const TRAIL_FRAMES: usize = 45;
/// Line radius of the rope, in string lengths.
const ROPE_RADIUS: f32 = 0.006;
/// Largest tension on the colour scale (the support tension of a swing from rest ≲ 5/4).
const SCALE_MAX: f64 = 1.25;

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
    rec: RecordingStream,
    /// One per method of the current run.
    lanes: Vec<LaneLog>,
    series_sent: Instant,
    /// Where the current run's t = 0 and step 0 lie on the timelines.
    time_offset: f64,
    step_offset: u64,
    /// The current run's `--tolerance`, drawn beside the estimate.
    tolerance: Option<f64>,
}

impl RopeLogger {
    /// Logs what never changes: the support, the colour scale, and the series' names and
    /// colours.
    pub fn new(rec: RecordingStream) -> rerun::RecordingStreamResult<Self> {
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
        Self::log_scale(&rec)?;
        Self::log_profile_axes(&rec)?;
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
        for (entity, name, [r, g, b], _) in SERIES {
            rec.log_static(
                entity,
                &rerun::SeriesLines::new()
                    .with_names([name])
                    .with_colors([rerun::Color::from_rgb(r, g, b)]),
            )?;
        }
        Ok(Self {
            rec,
            lanes: vec![LaneLog::alone()],
            series_sent: Instant::now(),
            time_offset: 0.0,
            step_offset: 0,
            tolerance: None,
        })
    }

    /// A static colour bar below the swing, F from 0 to [`SCALE_MAX`], labelled at its ends.
    /// Spanning the swing's width, it also keeps the view's extent steady.
    fn log_scale(rec: &RecordingStream) -> rerun::RecordingStreamResult<()> {
        let pieces = 25;
        let (x0, width, y) = (-1.0f32, 2.0f32, 1.12f32);
        let strips = (0..pieces).map(|i| {
            let a = x0 + width * i as f32 / pieces as f32;
            let b = x0 + width * (i + 1) as f32 / pieces as f32;
            [[a, y], [b, y]]
        });
        let colors = (0..pieces).map(|i| {
            let f = SCALE_MAX * (i as f64 + 0.5) / pieces as f64;
            tension_colour(f)
        });
        let mut labels = vec![String::new(); pieces];
        labels[pieces / 2] = format!("tension: red F = 0 … yellow F ≥ {SCALE_MAX} m g");
        rec.log_static(
            path::SCALE,
            &rerun::LineStrips2D::new(strips)
                .with_colors(colors)
                .with_radii([0.02])
                .with_labels(labels),
        )
    }

    /// Static axes for the tension profile: s from the support (0) to the tip (1) along the
    /// bottom, F drawn upward with guide lines at F = 0.5, 1, 1.5 and 2.
    fn log_profile_axes(rec: &RecordingStream) -> rerun::RecordingStreamResult<()> {
        let grey = rerun::Color::from_unmultiplied_rgba(160, 160, 160, 140);
        let mut strips = vec![[[0.0f32, 0.0], [1.0, 0.0]], [[0.0, 0.0], [0.0, -2.0]]];
        let mut labels = vec![String::new(), String::new()];
        for f in [0.5f32, 1.0, 1.5, 2.0] {
            strips.push([[0.0, -f], [1.0, -f]]);
            labels.push(format!("F = {f}"));
        }
        rec.log_static(
            path::PROFILE_AXES,
            &rerun::LineStrips2D::new(strips)
                .with_radii([0.002])
                .with_colors([grey])
                .with_labels(labels),
        )?;
        // The s axis's ticks (y points down); the view's title names the axis.
        let ticks = [0.0f32, 0.25, 0.5, 0.75, 1.0];
        // Just above the axis: the view fits its data, and a label below it would be cut.
        let points: Vec<[f32; 2]> = ticks.iter().map(|&s| [s, -0.08]).collect();
        let names: Vec<String> = ticks.iter().map(|s| format!("s = {s}")).collect();
        rec.log_static(
            path::PROFILE_TICKS,
            &rerun::Points2D::new(points)
                .with_radii([0.006])
                .with_colors([grey])
                .with_labels(names)
                .with_show_labels(true),
        )
    }

    /// The `sim_time` and `step` columns of `frames`, placed after the runs before.
    fn frame_times(&self, frames: &[&Frame]) -> [rerun::TimeColumn; 2] {
        let (time_offset, step_offset) = (self.time_offset, self.step_offset);
        timelines(
            frames.iter().map(|f| time_offset + f.time),
            frames.iter().map(|f| (step_offset + f.step) as i64),
        )
    }

    /// Logs a batch of frames, in order, on the `sim_time` and `step` timelines: one row per
    /// frame and entity, sent as columns (one chunk per entity for the whole batch, far
    /// cheaper than a log call per frame and entity).
    pub fn log_frames(&mut self, frames: &[Frame]) -> rerun::RecordingStreamResult<()> {
        let side_by_side = self.lanes.len() > 1;
        if side_by_side {
            self.log_shared_shapes(frames)?;
        }
        for lane in 0..self.lanes.len() {
            let mine: Vec<&Frame> = frames.iter().filter(|f| self.lanes[lane].owns(f)).collect();
            if mine.is_empty() {
                continue;
            }
            if !side_by_side {
                self.log_rope(lane, &mine)?;
                self.log_tip_and_trail(lane, &mine)?;
                self.log_tension_profile(lane, &mine)?;
            }
            self.log_tolerance_passed(lane, &mine)?;
            self.gather_series(lane, &mine);
        }
        let gathered: usize = self.lanes.iter().map(|l| l.series.len()).sum();
        let (most, wait) = match self.lanes.len() {
            1 => (SERIES_FRAMES, SERIES_WAIT),
            lanes => (SIDE_BY_SIDE_SERIES_FRAMES * lanes, SIDE_BY_SIDE_SERIES_WAIT),
        };
        if gathered >= most || self.series_sent.elapsed() >= wait {
            self.send_series()?;
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
        for f in frames.iter().filter(|f| f.tolerance_exceeded) {
            let tip = f.error_estimate.map_or(f64::NAN, |e| e.tip);
            let eps = self.tolerance.unwrap_or(f64::NAN);
            let times = timelines(
                [self.time_offset + f.time],
                [(self.step_offset + f.step) as i64],
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
                        "the estimated tip error {tip:.1e} passed the tolerance {eps:.1e} at t = {:.3}",
                        f.time
                    ))
                    .with_level(rerun::TextLogLevel::WARN)
                    .columns_of_unit_batches()?,
            )?;
        }
        Ok(())
    }

    /// The rope: one 2-point strip per segment, coloured by its tension.
    fn log_rope(&self, lane: usize, frames: &[&Frame]) -> rerun::RecordingStreamResult<()> {
        let mut strips = Vec::new();
        let mut colours = Vec::new();
        let mut lengths = Vec::with_capacity(frames.len());
        for f in frames {
            lengths.push(f.tension.len());
            strips.extend(f.nodes.windows(2).map(|w| [xy(&w[0]), xy(&w[1])]));
            colours.extend(f.tension.iter().map(|&t| tension_colour(t)));
        }
        self.rec.send_columns(
            self.lanes[lane].at(path::SEGMENTS),
            self.frame_times(frames),
            rerun::LineStrips2D::update_fields()
                .with_strips(strips)
                .with_colors(colours)
                .columns(lengths)?,
        )
    }

    /// Several methods side by side: each instant's ropes, tips and tension profiles as one
    /// row of three entities shared by the methods (a method that stopped is no longer in
    /// them). A browser's viewer keeps every chunk it is sent, each with its own schema and
    /// index: three entities an instant instead of three per method, and the ropes in
    /// [`SHADE`]s of tension (a strip per run of one shade, about half the points), make
    /// what it keeps grow about a quarter as fast.
    fn log_shared_shapes(&self, frames: &[Frame]) -> rerun::RecordingStreamResult<()> {
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
        let lane_of = |f: &Frame| {
            self.lanes
                .iter()
                .find(|l| l.owns(f))
                .map_or((rerun::Color::from_rgb(20, 20, 20), ""), |l| {
                    (l.colour, l.name)
                })
        };
        let (mut ropes, mut rope_colours, mut rope_lengths) = (Vec::new(), Vec::new(), Vec::new());
        let (mut tips, mut tip_colours, mut names) = (Vec::new(), Vec::new(), Vec::new());
        let (mut profiles, mut profile_colours) = (Vec::new(), Vec::new());
        let mut per_instant = Vec::with_capacity(instants.len());
        for instant in &instants {
            let before = ropes.len();
            for f in instant {
                let nodes: Vec<[f32; 2]> = f.nodes.iter().map(xy).collect();
                let (strips, colours) = shaded_strips(&nodes, &f.tension, SHADE);
                ropes.extend(strips);
                rope_colours.extend(colours);
                let (colour, name) = lane_of(f);
                tips.push(xy(&f.tip()));
                tip_colours.push(colour);
                names.push(name);
                profiles.push(profile(f));
                profile_colours.push(colour);
            }
            rope_lengths.push(ropes.len() - before);
            per_instant.push(instant.len());
        }
        let times = || {
            [rerun::TimeColumn::new_duration_secs(
                SIM_TIME,
                instants.iter().map(|i| self.time_offset + i[0].time),
            )]
        };
        self.rec.send_columns(
            path::SEGMENTS,
            times(),
            rerun::LineStrips2D::update_fields()
                .with_strips(ropes)
                .with_colors(rope_colours)
                .columns(rope_lengths)?,
        )?;
        self.rec.send_columns(
            path::TIPS,
            times(),
            rerun::Points2D::update_fields()
                .with_positions(tips)
                .with_colors(tip_colours)
                .with_labels(names)
                .columns(per_instant.iter().copied())?,
        )?;
        self.rec.send_columns(
            path::PROFILES,
            times(),
            rerun::LineStrips2D::update_fields()
                .with_strips(profiles)
                .with_colors(profile_colours)
                .columns(per_instant)?,
        )
    }

    /// The tip, and its trail as it stood at each frame.
    fn log_tip_and_trail(
        &mut self,
        lane: usize,
        frames: &[&Frame],
    ) -> rerun::RecordingStreamResult<()> {
        let tips: Vec<[f32; 2]> = frames.iter().map(|f| xy(&f.tip())).collect();
        let times = self.frame_times(frames);
        let lane = &mut self.lanes[lane];
        self.rec.send_columns(
            lane.at(path::TIP),
            times.clone(),
            rerun::Points2D::update_fields()
                .with_positions(tips.iter().copied())
                .columns_of_unit_batches()?,
        )?;
        let trail = &mut lane.trail;
        let trails: Vec<Vec<[f32; 2]>> = tips
            .iter()
            .map(|&tip| {
                if trail.len() == TRAIL_FRAMES {
                    trail.pop_front();
                }
                trail.push_back(tip);
                trail.iter().copied().collect()
            })
            .collect();
        self.rec.send_columns(
            lane.at(path::TRAIL),
            times,
            rerun::LineStrips2D::update_fields()
                .with_strips(trails)
                .columns_of_unit_batches()?,
        )
    }

    /// F(s) drawn upward: x = s, y = −F (the 2D view's y points down).
    fn log_tension_profile(
        &self,
        lane: usize,
        frames: &[&Frame],
    ) -> rerun::RecordingStreamResult<()> {
        let profiles: Vec<Vec<[f32; 2]>> = frames.iter().map(|f| profile(f)).collect();
        self.rec.send_columns(
            self.lanes[lane].at(path::PROFILE),
            self.frame_times(frames),
            rerun::LineStrips2D::update_fields()
                .with_strips(profiles)
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
        for lane in &mut self.lanes {
            send_lane_series(&self.rec, lane, self.tolerance)?;
        }
        Ok(())
    }
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
            rec.send_columns(
                lane.at(entity),
                timelines(kept().map(|r| r.0), kept().map(|r| r.1)),
                rerun::Scalars::new(kept().map(|r| r.2[i])).columns_of_unit_batches()?,
            )?;
        }
        if let Some(eps) = tolerance {
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
    /// What is running, where the run starts: the caption over the rope, and the parameters.
    fn log_run_text(&self, headline: String, markdown: String) -> Result<(), RecordingError> {
        let times = || timelines([self.time_offset], [self.step_offset as i64]);
        self.rec.send_columns(
            path::CAPTION,
            times(),
            rerun::Points2D::update_fields()
                .with_labels([headline])
                .columns_of_unit_batches()?,
        )?;
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

    /// How one method of several side by side is drawn in the plots: in its own colour,
    /// named by it.
    fn style_lane(&self, lane: &LaneLog) -> rerun::RecordingStreamResult<()> {
        let (method, colour) = (lane.name, lane.colour);
        for (entity, name, ..) in SERIES.into_iter().filter(|(e, ..)| lane.sends(e)) {
            let name = if entity.starts_with("energy/") {
                format!("{method} {name}")
            } else {
                method.to_owned()
            };
            self.rec.log_static(
                lane.at(entity),
                &rerun::SeriesLines::new()
                    .with_names([name])
                    .with_colors([colour]),
            )?;
        }
        Ok(())
    }
}

/// F(s) of a frame drawn upward: x = s at each segment's middle, y = −F (the 2D view's y
/// points down).
fn profile(f: &Frame) -> Vec<[f32; 2]> {
    let n = f.tension.len() as f32;
    f.tension
        .iter()
        .enumerate()
        .map(|(i, &t)| [(i as f32 + 0.5) / n, -(t as f32)])
        .collect()
}

/// A point as the viewer takes it.
fn xy(p: &Point) -> [f32; 2] {
    [p.x as f32, p.y as f32]
}

/// A recording of runs, one after another on the timelines: each starts where the one
/// before it ended (`--loop`), with its parameters logged there and a fresh trail.
impl FrameSink for RopeLogger {
    type Error = RecordingError;

    fn begin_run(&mut self, plan: &RunPlan) -> Result<(), RecordingError> {
        // What was gathered belongs to the run before, and to its tolerance.
        self.send_series()?;
        self.lanes = vec![LaneLog::alone()];
        self.tolerance = plan.tolerance;
        self.log_run_text(plan.headline(), plan.markdown())
    }

    fn begin_lanes(&mut self, plans: &[RunPlan]) -> Result<(), RecordingError> {
        self.send_series()?;
        self.tolerance = None; // (--tolerance chooses one method: never side by side)
        self.lanes = plans
            .iter()
            .enumerate()
            .map(|(i, p)| LaneLog::of(i, p))
            .collect();
        for lane in &self.lanes {
            self.style_lane(lane)?;
        }
        // The shared shapes' styling; their colours and names come with each instant.
        self.rec.log_static(
            path::TIPS,
            &rerun::Points2D::update_fields()
                .with_radii([0.018])
                .with_show_labels(true),
        )?;
        self.rec.log_static(
            path::PROFILES,
            &rerun::LineStrips2D::update_fields().with_radii([0.008]),
        )?;
        let names: Vec<&str> = self.lanes.iter().map(|l| l.name).collect();
        self.rec.log_static(
            path::LEGEND,
            &rerun::Points2D::new((0..plans.len()).map(|i| [-0.85f32, -0.55 + 0.1 * i as f32]))
                .with_radii([0.025])
                .with_colors(self.lanes.iter().map(|l| l.colour))
                .with_labels(names.iter().map(|n| format!("{n} (tip)")))
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
        Ok(())
    }

    fn frames(&mut self, frames: &[Frame]) -> Result<(), RecordingError> {
        Ok(self.log_frames(frames)?)
    }

    fn flush(&mut self) -> Result<(), RecordingError> {
        self.send_series()?;
        Ok(self.rec.flush_with_timeout(FLUSH_TIMEOUT)?)
    }

    /// Time series still gathered keep their own times.
    fn end_run(&mut self, time: f64, steps: u64) {
        self.time_offset += time;
        self.step_offset += steps;
    }
}
