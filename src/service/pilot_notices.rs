//! What `--tolerance`'s pilots measured, as the run announces it: a line per method, from
//! the pilots' own estimates to the model fitted to them (or why a method was not flown).

use crate::methods::MethodKind;
use crate::plan::committed::Source;
use crate::plan::pilot::{self, PassedOver, PassedOverWhy, Pilots};

/// What the pilots of `--tolerance` measured, a line per method.
pub fn pilot_lines(pilots: &Pilots, duration: f64) -> String {
    let seconds = pilots.seconds();
    let mut text = format!(
        "rope: tolerance pilots: to t = {}, {seconds:.2} s of CPU; the largest live tip estimate at each N flown:",
        duration.min(pilot::WINDOW)
    );
    let held = pilots.flown.iter().any(|p| p.held_at.is_some());
    for p in &pilots.flown {
        let measured: Vec<String> = p
            .measured
            .iter()
            .map(|(n, e)| format!("{e:.1e} at N = {n}"))
            .collect();
        let measured = measured.join(", ");
        let what = match (&p.diverged, &p.model, p.held_at) {
            (Some(d), _, _) => format!("ruled out, a pilot diverged: {d}"),
            (None, _, None) if p.measured_by.is_some() => format!(
                "not flown: its {} are the {}'s, whose pilots measure their error",
                p.method.descriptor().discretization,
                p.measured_by.map_or("", MethodKind::name)
            ),
            (None, _, None) if !p.flew() => not_flown(p.passed_over.as_ref(), held),
            (None, _, None) if p.measured.is_empty() && !p.shadow_lost.is_empty() => {
                let lost: Vec<String> = p
                    .shadow_lost
                    .iter()
                    .map(|(n, why)| format!("at N = {n}, {why}"))
                    .collect();
                format!(
                    "not measured: the method ran, but its error estimate's coarser run (the shadow at N/2) diverged ({})",
                    lost.join("; ")
                )
            }
            (None, _, Some(n)) => format!(
                "{measured} → holds the tolerance at N = {n} by its own estimate (×{} safety)",
                pilot::SAFETY
            ),
            (None, Some(m), None) => {
                // Three significant digits, however small the constant.
                let constant = match m.constant >= 0.01 {
                    true => format!("{:.3}", m.constant),
                    false => format!("{:.2e}", m.constant),
                };
                format!(
                    "{measured} → error ≈ {constant} h^{:.2} (×{:.1} safety)",
                    m.order, m.safety
                )
            }
            (None, None, None) => format!("{measured} → no model fitted"),
        };
        text += &format!("\n  {}: {what}", p.method);
    }
    text
}

/// Why a method's pilots did not fly: the climb passed them over, or ended before them (a
/// pilot `held`, or the next would have cost more than the best run known).
fn not_flown(passed_over: Option<&PassedOver>, held: bool) -> String {
    let Some(passed_over) = passed_over else {
        return match held {
            true => "not flown: another method's pilot held first".to_owned(),
            false => {
                "not flown: the next pilot would have cost more than the best run known".to_owned()
            }
        };
    };
    // "16", "16 and 32", "16, 32 and 64".
    let listed =
        |levels: &[usize]| -> Vec<String> { levels.iter().map(usize::to_string).collect() };
    let levels = match passed_over.levels.split_last() {
        Some((last, before)) if !before.is_empty() => {
            format!("{} and {last}", listed(before).join(", "))
        }
        _ => listed(&passed_over.levels).concat(),
    };
    match passed_over.why {
        PassedOverWhy::CannotHold(source) => {
            let model = match source {
                Source::Atlas => "the release atlas",
                Source::Theory => "the linear theory",
                Source::Law => "its committed law",
            };
            format!(
                "not flown: {model} puts its error at N = {levels} past the tolerance, and a pilot could change the choice only by holding there"
            )
        }
        PassedOverWhy::CannotSave => format!(
            "not flown: its pilot at N = {levels} could not save what it costs beside the best run known"
        ),
    }
}
