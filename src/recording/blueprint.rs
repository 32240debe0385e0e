//! The viewer's layout: the rope and its tension profile on the left, the time series on
//! the right. One small function per view.

use super::entities::{SIM_TIME, path};
use crate::run::RunPlan;
use crate::run::config::trimmed_fixed;
use crate::run::simulate::REFERENCE_STEP;
use rerun::blueprint::components::PanelState;
use rerun::blueprint::{
    Blueprint, BlueprintPanel, ContainerLike, Horizontal, SelectionPanel, Spatial2DView, Tabs,
    TextDocumentView, TextLogView, TimePanel, TimeSeriesView, Vertical,
};

/// The whole layout: the views get the window (the blueprint and selection panels start
/// collapsed; the time panel, which scrubs the run, keeps its time bar). `headline` names
/// the method, N and k over the rope when every run of the recording shares them. With
/// several methods side by side (`lanes`, a plan each), their ropes share the rope view,
/// each in its method's hue (named in the view's legend), and the energy panel gives way to
/// their distance from the most accurate one's string. A `sweep` of a shake's frequency gets
/// a view of the free end's largest swing against Ω.
pub fn blueprint(headline: Option<&str>, lanes: &[RunPlan], sweep: bool) -> Blueprint {
    window([
        rope_view(headline, lanes.len() > 1).into(),
        tension_profile_view().into(),
        plots(lanes, sweep).into(),
    ])
}

/// Three columns (rope, profile, plots) that get the window: the blueprint and selection
/// panels start collapsed; the time panel, which scrubs the run, keeps only its time bar, so
/// that the plots get the height their axes need (expanded, it left each log plot two ticks).
fn window(columns: [ContainerLike; 3]) -> Blueprint {
    Blueprint::new(Horizontal::new(columns).with_column_shares([4.0, 3.0, 4.0]))
        .with_auto_views(false)
        .with_blueprint_panel(BlueprintPanel::from_state(PanelState::Collapsed))
        .with_selection_panel(SelectionPanel::from_state(PanelState::Collapsed))
        .with_time_panel(
            TimePanel::new()
                .with_timeline(SIM_TIME)
                .with_state(PanelState::Collapsed),
        )
}

/// The plots: energy (side by side, the disagreement; a fold, its theory: the free end's fall,
/// speed and the support's tension; a shake, the free end's sideways swing against the steady
/// state, and the energy balance with the support's work), its deviation, the error estimate,
/// and the diagnostics' tabs.
fn plots(lanes: &[RunPlan], sweep: bool) -> Vertical {
    let fold = lanes
        .iter()
        .all(|p| matches!(p.scene, crate::model::Scene::Fold { .. }));
    let shake = lanes.iter().all(|p| p.scene.support().moves());
    match lanes {
        [_] if shake && sweep => Vertical::new([
            Spatial2DView::new(
                "Sweep: the free end's largest swing against Ω (log scale), resonances marked",
            )
            .with_origin(path::SWEEP)
            .into(),
            series_view(
                "Free end's sideways x: measured, linear theory, the support",
                path::SIDEWAYS,
            )
            .into(),
            TimeSeriesView::new("log₁₀ |E − E₀ − W|: the energy balance")
                .with_origin(path::LOG_BALANCE)
                .into(),
            diagnostics(false).into(),
        ])
        .with_row_shares([3.0, 1.5, 1.0, 1.5]),
        [_] if shake => Vertical::new([
            series_view(
                "Free end's sideways x: measured, the linear steady state, the support",
                path::SIDEWAYS,
            )
            .into(),
            TimeSeriesView::new("Energy gained E − E₀ and the support's work W")
                .with_contents([path::GAINED, path::SUPPORT_WORK])
                .into(),
            TimeSeriesView::new("log₁₀ |E − E₀ − W|: the energy balance")
                .with_origin(path::LOG_BALANCE)
                .into(),
            diagnostics(false).into(),
        ]),
        [_] if fold => Vertical::new([
            series_view(
                "Free end's fall x(t): measured, Calkin–March, free fall",
                path::FALL,
            )
            .into(),
            series_view(
                "Free end's speed against Calkin–March at its fall",
                path::SPEED,
            )
            .into(),
            series_view(
                "Support tension F_0, raw and averaged over 0.05, against (1 + x)/2 + v²/4",
                path::TENSION,
            )
            .into(),
            deviation_view().into(),
            diagnostics(false).into(),
        ]),
        [_, _, ..] => Vertical::new([
            deviation_view().into(),
            disagreement_view(lanes).into(),
            error_view().into(),
            diagnostics(true).into(),
        ]),
        _ => Vertical::new([
            energy_view().into(),
            deviation_view().into(),
            error_view().into(),
            diagnostics(false).into(),
        ]),
    }
}

/// The layout for viewers of a run that never ends: the live rope, and under the tension
/// profile the rope "then", at the time cursor, from the history kept every
/// `shape_interval` time units; the plots as for a run of every frame.
pub fn live(
    headline: Option<&str>,
    lanes: &[RunPlan],
    shape_interval: f64,
    sweep: bool,
) -> Blueprint {
    window([
        live_rope_view(headline, lanes.len() > 1).into(),
        Vertical::new([
            then_rope_view(shape_interval).into(),
            tension_profile_view().into(),
        ])
        .with_row_shares([3.0, 2.0])
        .into(),
        plots(lanes, sweep).into(),
    ])
}

/// How ropes side by side are coloured, for the rope views' titles.
const HUED: &str = "each in its method's colour, shaded by tension";

/// The live rope: it replaces itself at every frame, whatever the time cursor says.
fn live_rope_view(headline: Option<&str>, side_by_side: bool) -> Spatial2DView {
    let title = match headline {
        Some(headline) => format!("Rope now (live): {headline}"),
        None if side_by_side => format!("Ropes now (live, {HUED})"),
        None => "Rope now (live, coloured by tension)".to_owned(),
    };
    Spatial2DView::new(title).with_origin("rope")
}

/// The rope at the time cursor, from the history: scrub the timeline to see it then.
fn then_rope_view(shape_interval: f64) -> Spatial2DView {
    Spatial2DView::new(format!(
        "Rope then: at the time cursor (kept every {} time units; scrub the timeline)",
        trimmed_fixed(shape_interval, 3)
    ))
    .with_origin("then")
}

/// The rope, coloured by tension, with its support, tip, trail and colour scale; the title
/// says what is running (the support's label says it too, run by run).
fn rope_view(headline: Option<&str>, side_by_side: bool) -> Spatial2DView {
    let title = match headline {
        Some(headline) => format!("Rope: {headline}"),
        None if side_by_side => format!("Ropes ({HUED})"),
        None => "Rope (coloured by tension)".to_owned(),
    };
    Spatial2DView::new(title).with_origin("rope")
}

/// F(s) along the string, drawn upward over its axes.
fn tension_profile_view() -> Spatial2DView {
    Spatial2DView::new("Tension F(s), s: support 0 … tip 1").with_origin("tension")
}

/// Kinetic, potential and total energy.
fn energy_view() -> TimeSeriesView {
    TimeSeriesView::new("Energy").with_contents([path::KINETIC, path::POTENTIAL, path::TOTAL])
}

/// The report's accuracy criterion, (E − E_ref)/|E_ref|, as its decimal logarithm: Rerun's
/// plots have no log axis, and a deviation of 1e-12 on a linear one reads "−0.000 000…".
fn deviation_view() -> TimeSeriesView {
    TimeSeriesView::new(format!(
        "log₁₀ |E − E_ref|/|E_ref| (E_ref: step {REFERENCE_STEP})"
    ))
    .with_origin(path::LOG_DEVIATION)
}

/// The live error estimate, against the tolerance when there is one, as decimal logarithms.
fn error_view() -> TimeSeriesView {
    TimeSeriesView::new("log₁₀ estimated error (vs. N/2)").with_origin(path::LOG_ERROR)
}

/// How far each method's string is from the most accurate one's, as a decimal logarithm.
fn disagreement_view(lanes: &[RunPlan]) -> TimeSeriesView {
    let best = lanes
        .iter()
        .min_by_key(|p| p.method.accuracy_rank())
        .map_or("the most accurate", |p| p.method.name());
    TimeSeriesView::new(format!("log₁₀ distance from {best}'s string (at equal s)"))
        .with_origin(path::LOG_DISAGREEMENT)
}

/// Support tension, the run's parameters and events, tip speed and acceleration, and the
/// joints, as tabs: the text tabs early, where a narrow window still shows their names.
/// Side by side, the methods' total energies join them.
fn diagnostics(side_by_side: bool) -> Tabs {
    let mut tabs = vec![
        ContainerLike::from(series_view("Support tension F_0", path::SUPPORT_TENSION)),
        TextDocumentView::new("Parameters")
            .with_origin(path::PARAMETERS)
            .into(),
        TextLogView::new("Events").with_origin(path::EVENTS).into(),
        series_view("Tip speed", path::TIP_SPEED).into(),
        series_view("Tip acceleration", path::TIP_ACCELERATION).into(),
        TimeSeriesView::new("Joints (rattle, midpoint)")
            .with_origin("constraint")
            .into(),
    ];
    if side_by_side {
        tabs.insert(3, series_view("Total energy", path::TOTAL).into());
    }
    Tabs::new(tabs)
}

/// A time series view of one entity and what is under it (a theory's quantity: its
/// measurement and each prediction in one plot).
fn series_view(title: &str, entity: &str) -> TimeSeriesView {
    TimeSeriesView::new(title).with_origin(entity)
}
