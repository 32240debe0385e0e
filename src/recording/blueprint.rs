//! The viewer's layout: the rope and its tension profile on the left, the time series on
//! the right. One small function per view.

use super::logger::{SIM_TIME, path};
use crate::run::simulate::REFERENCE_STEP;
use rerun::blueprint::components::PanelState;
use rerun::blueprint::{
    Blueprint, BlueprintPanel, ContainerLike, Horizontal, SelectionPanel, Spatial2DView, Tabs,
    TextDocumentView, TextLogView, TimePanel, TimeSeriesView, Vertical,
};

/// The whole layout: the views get the window (the blueprint and selection panels start
/// collapsed; the time panel, which scrubs the run, stays).
pub fn blueprint() -> Blueprint {
    Blueprint::new(
        Horizontal::new([
            rope_view().into(),
            tension_profile_view().into(),
            Vertical::new([
                energy_view().into(),
                deviation_view().into(),
                error_view().into(),
                diagnostics().into(),
            ])
            .into(),
        ])
        .with_column_shares([4.0, 3.0, 4.0]),
    )
    .with_auto_views(false)
    .with_blueprint_panel(BlueprintPanel::from_state(PanelState::Collapsed))
    .with_selection_panel(SelectionPanel::from_state(PanelState::Collapsed))
    .with_time_panel(
        TimePanel::new()
            .with_timeline(SIM_TIME)
            .with_state(PanelState::Expanded),
    )
}

/// The rope, coloured by tension, with its support, tip, trail and colour scale.
fn rope_view() -> Spatial2DView {
    Spatial2DView::new("Rope (coloured by tension)").with_origin("rope")
}

/// F(s) along the string, drawn upward over its axes.
fn tension_profile_view() -> Spatial2DView {
    Spatial2DView::new("Tension profile F(s), drawn upward").with_origin("tension")
}

/// Kinetic, potential and total energy.
fn energy_view() -> TimeSeriesView {
    TimeSeriesView::new("Energy").with_contents([path::KINETIC, path::POTENTIAL, path::TOTAL])
}

/// The report's accuracy criterion, (E − E_ref)/|E_ref|.
fn deviation_view() -> TimeSeriesView {
    TimeSeriesView::new(format!(
        "Energy deviation (relative to step {REFERENCE_STEP})"
    ))
    .with_origin(path::DEVIATION)
}

/// The live error estimate, against the tolerance when there is one.
fn error_view() -> TimeSeriesView {
    TimeSeriesView::new("Estimated error (against the run at N/2)").with_origin("error")
}

/// Support tension, tip speed and acceleration, and the run's parameters, as tabs.
fn diagnostics() -> Tabs {
    Tabs::new([
        ContainerLike::from(series_view("Support tension F_0", path::SUPPORT_TENSION)),
        series_view("Tip speed", path::TIP_SPEED).into(),
        series_view("Tip acceleration", path::TIP_ACCELERATION).into(),
        TimeSeriesView::new("Joints (rattle, midpoint)")
            .with_origin("constraint")
            .into(),
        TextLogView::new("Events").with_origin(path::EVENTS).into(),
        TextDocumentView::new("Parameters")
            .with_origin(path::PARAMETERS)
            .into(),
    ])
}

/// A time series view of one entity.
fn series_view(title: &str, entity: &str) -> TimeSeriesView {
    TimeSeriesView::new(title).with_origin(entity)
}
