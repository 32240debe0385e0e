//! Writes frames to a Rerun recording stream: the rope coloured by tension, the tension
//! profile, energy and tip time series, the run's parameters, and a blueprint that lays them
//! out. Knows nothing of the equations: it draws what a [`Frame`] holds.

use crate::color::tension_rgb;
use crate::simulate::Frame;
use rerun::RecordingStream;
use rerun::blueprint::{
    Blueprint, ContainerLike, Horizontal, Spatial2DView, Tabs, TextDocumentView, TimeSeriesView,
    Vertical,
};
use std::collections::VecDeque;

/// Entity paths: the contract with tests and with users' own queries.
pub mod path {
    pub const SEGMENTS: &str = "rope/segments";
    pub const SUPPORT: &str = "rope/support";
    pub const TIP: &str = "rope/tip";
    pub const TRAIL: &str = "rope/trail";
    pub const SCALE: &str = "rope/tension_scale";
    pub const PROFILE: &str = "tension/profile";
    pub const PROFILE_AXES: &str = "tension/axes";
    pub const KINETIC: &str = "energy/kinetic";
    pub const POTENTIAL: &str = "energy/potential";
    pub const TOTAL: &str = "energy/total";
    pub const DEVIATION: &str = "energy/deviation";
    pub const SUPPORT_TENSION: &str = "support/tension";
    pub const TIP_SPEED: &str = "tip/speed";
    pub const TIP_ACCELERATION: &str = "tip/acceleration";
    pub const PARAMETERS: &str = "parameters";
}

/// Timelines: simulated seconds, and the step count.
pub const SIM_TIME: &str = "sim_time";
pub const STEP: &str = "step";

/// How many frames of the tip's path the trail keeps.
const TRAIL_FRAMES: usize = 45;
/// Line radius of the rope, in string lengths.
const ROPE_RADIUS: f32 = 0.006;
/// Largest tension on the colour scale (the support tension of a swing from rest ≲ 5/4).
const SCALE_MAX: f64 = 1.25;

/// The viewer layout: rope and tension profile on the left, time series on the right.
pub fn blueprint() -> Blueprint {
    let rope = Spatial2DView::new("Rope (coloured by tension)").with_origin("rope");
    let profile =
        rerun::blueprint::BarChartView::new("Tension profile F(s)").with_origin(path::PROFILE);
    let params = TextDocumentView::new("Parameters").with_origin(path::PARAMETERS);
    let energy =
        TimeSeriesView::new("Energy").with_contents([path::KINETIC, path::POTENTIAL, path::TOTAL]);
    let deviation =
        TimeSeriesView::new("Energy deviation (relative to step 10)").with_origin(path::DEVIATION);
    let diagnostics = Tabs::new([
        ContainerLike::from(
            TimeSeriesView::new("Support tension F_0").with_origin(path::SUPPORT_TENSION),
        ),
        TimeSeriesView::new("Tip speed")
            .with_origin(path::TIP_SPEED)
            .into(),
        TimeSeriesView::new("Tip acceleration")
            .with_origin(path::TIP_ACCELERATION)
            .into(),
    ]);
    Blueprint::new(
        Horizontal::new([
            Vertical::new([
                rope.into(),
                Tabs::new([profile.into(), params.into()]).into(),
            ])
            .with_row_shares([3.0, 2.0])
            .into(),
            Vertical::new([energy.into(), deviation.into(), diagnostics.into()]).into(),
        ])
        .with_column_shares([3.0, 2.0]),
    )
    .with_auto_views(false)
    .with_time_panel(rerun::blueprint::TimePanel::new().with_timeline(SIM_TIME))
}

/// Streams frames of one run into a recording.
pub struct RopeLogger {
    rec: RecordingStream,
    trail: VecDeque<[f32; 2]>,
}

impl RopeLogger {
    /// Logs what does not change over the run: the parameters text, the support, the colour
    /// scale and the series' names and colours.
    pub fn new(
        rec: RecordingStream,
        parameters_markdown: &str,
    ) -> rerun::RecordingStreamResult<Self> {
        rec.log_static(
            path::PARAMETERS,
            &rerun::TextDocument::from_markdown(parameters_markdown),
        )?;
        rec.log_static(
            path::SUPPORT,
            &rerun::Points2D::new([[0.0f32, 0.0]])
                .with_radii([0.02])
                .with_colors([rerun::Color::from_rgb(90, 90, 90)])
                .with_labels(["support"]),
        )?;
        Self::log_scale(&rec)?;
        Self::log_profile_axes(&rec)?;
        let series = [
            (path::KINETIC, "kinetic", [230, 120, 30]),
            (path::POTENTIAL, "potential", [60, 120, 220]),
            (path::TOTAL, "total", [220, 220, 220]),
            (path::DEVIATION, "(E − E_ref)/|E_ref|", [200, 40, 40]),
            (path::SUPPORT_TENSION, "F_0", [200, 150, 0]),
            (path::TIP_SPEED, "|v_tip|", [40, 150, 80]),
            (path::TIP_ACCELERATION, "|a_tip|", [120, 60, 160]),
        ];
        for (entity, name, [r, g, b]) in series {
            rec.log_static(
                entity,
                &rerun::SeriesLines::new()
                    .with_names([name])
                    .with_colors([rerun::Color::from_rgb(r, g, b)]),
            )?;
        }
        Ok(Self {
            rec,
            trail: VecDeque::with_capacity(TRAIL_FRAMES),
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
            let [r, g, b] = tension_rgb(f);
            rerun::Color::from_rgb(r, g, b)
        });
        let mut labels = vec![String::new(); pieces];
        labels[0] = "tension F = 0".into();
        labels[pieces - 1] = format!("F ≥ {SCALE_MAX} m g");
        rec.log_static(
            path::SCALE,
            &rerun::LineStrips2D::new(strips)
                .with_colors(colors)
                .with_radii([0.02])
                .with_labels(labels),
        )
    }

    /// Static axes for the tension profile: s from the support (0) to the tip (1) along the
    /// bottom, F drawn upward with guide lines at F = 0.5, 1 and 1.5.
    fn log_profile_axes(rec: &RecordingStream) -> rerun::RecordingStreamResult<()> {
        let grey = rerun::Color::from_unmultiplied_rgba(160, 160, 160, 140);
        let mut strips = vec![[[0.0f32, 0.0], [1.0, 0.0]], [[0.0, 0.0], [0.0, -1.6]]];
        let mut labels = vec!["s (support 0 … tip 1)".to_owned(), String::new()];
        for f in [0.5f32, 1.0, 1.5] {
            strips.push([[0.0, -f], [1.0, -f]]);
            labels.push(format!("F = {f}"));
        }
        rec.log_static(
            path::PROFILE_AXES,
            &rerun::LineStrips2D::new(strips)
                .with_radii([0.002])
                .with_colors([grey])
                .with_labels(labels),
        )
    }

    /// Logs one frame on the `sim_time` and `step` timelines.
    pub fn log_frame(&mut self, frame: &Frame) -> rerun::RecordingStreamResult<()> {
        let rec = &self.rec;
        rec.set_time_sequence(STEP, frame.step as i64);
        rec.set_duration_secs(SIM_TIME, frame.time);
        let point = |p: &crate::geometry::Point| [p.x as f32, p.y as f32];
        let strips = frame.nodes.windows(2).map(|w| [point(&w[0]), point(&w[1])]);
        let colors = frame.tension.iter().map(|&f| {
            let [r, g, b] = tension_rgb(f);
            rerun::Color::from_rgb(r, g, b)
        });
        rec.log(
            path::SEGMENTS,
            &rerun::LineStrips2D::new(strips)
                .with_colors(colors)
                .with_radii([ROPE_RADIUS]),
        )?;
        let tip = point(&frame.tip());
        rec.log(
            path::TIP,
            &rerun::Points2D::new([tip])
                .with_radii([0.015])
                .with_colors([rerun::Color::from_rgb(20, 20, 20)]),
        )?;
        if self.trail.len() == TRAIL_FRAMES {
            self.trail.pop_front();
        }
        self.trail.push_back(tip);
        rec.log(
            path::TRAIL,
            &rerun::LineStrips2D::new([self.trail.iter().copied().collect::<Vec<_>>()])
                .with_radii([0.002])
                .with_colors([rerun::Color::from_unmultiplied_rgba(40, 40, 40, 110)]),
        )?;
        // F(s) drawn upward: x = s, y = −F (the 2D view's y points down).
        let n = frame.tension.len() as f32;
        let profile: Vec<[f32; 2]> = frame
            .tension
            .iter()
            .enumerate()
            .map(|(i, &f)| [(i as f32 + 0.5) / n, -(f as f32)])
            .collect();
        rec.log(
            path::PROFILE,
            &rerun::LineStrips2D::new([profile])
                .with_radii([0.008])
                .with_colors([rerun::Color::from_rgb(230, 150, 0)]),
        )?;
        let scalars = [
            (path::KINETIC, frame.energy.kinetic()),
            (path::POTENTIAL, frame.energy.potential),
            (path::TOTAL, frame.energy.total()),
            (path::DEVIATION, frame.energy_deviation),
            (path::SUPPORT_TENSION, frame.support_tension),
            (path::TIP_SPEED, frame.tip_velocity.norm()),
            (path::TIP_ACCELERATION, frame.tip_acceleration.norm()),
        ];
        for (entity, value) in scalars {
            rec.log(entity, &rerun::Scalars::single(value))?;
        }
        Ok(())
    }

    /// The recording stream, for flushing at the end.
    pub fn recording(&self) -> &RecordingStream {
        &self.rec
    }
}
