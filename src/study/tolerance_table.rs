//! The tolerance check ([`tolerance_check`](super::tolerance_check)) as Markdown, for
//! `docs/measurements.md`: how it was made, its references, then a row per scene and tolerance.

use super::tip_reference::{ConvergedTip, JUDGE_RATE, REFERENCE_RATE, REFERENCE_ROWS_RATE};
use super::tolerance_check::{CheckSpec, Checked, EstimateVerdict, Measured, REFERENCE_MARGIN};
use crate::methods::MethodKind;
use crate::plan::pilot;

/// The check as Markdown: the references, then a row per scene and tolerance.
pub fn markdown(spec: &CheckSpec, checked: &Checked, command: &str) -> String {
    let mut text = format!(
        "# `--tolerance` against the truth\n\n`{command}`\n\n\
         For each scene and EPS, the run `rope run --tolerance EPS --duration {}` makes (its \
         pilots, then the chosen method, N and k with its shadow at N/2) is compared at every \
         1/{JUDGE_RATE} of a time unit (its tip kept at every step, whatever its frames) with \
         the tip of a reference: the {} method (the graded \
         rods where their end rods do not spin on, a release from 20° up: their tip converges \
         faster through the whip) at N/2, N and 2N, extrapolated in N at the order the three show, N doubled from {} (up to {}, \
         and on up to {} where the order the runs show, or 2 if less, would reach it) until the \
         reference's own error is at most {REFERENCE_MARGIN} × the smallest EPS. Its \
         CPU (one thread, pilots included; where a pilot held, it was flown as the run and \
         not again, so the run's CPU is in the pilots') is set beside the cheapest run of the grid (every \
         method that can start, at N = {:?}, each at its default step and at its tolerance step \
         where that is another, without a shadow, up to the N where one of its runs holds the \
         smallest EPS and none costs less than the cheapest that holds; where none holds the smallest EPS the \
         reference can judge, on at N = {:?} up to the first N where one does) whose largest \
         error also holds EPS. A \
         tolerance is checked only where the reference's own error at every 1/{JUDGE_RATE} is \
         at most {REFERENCE_MARGIN} × EPS. Where `--references` gave a scene's reference, the \
         one of least own error is read instead of computed, at its rows: the method column \
         names its file. The verdict is what the \
         run's exit status would say (4 where its live estimate, at every step it shares with \
         its shadow, passed EPS) against the truth: a miss it did not say, or a false alarm \
         where the truth held within EPS/2, is a verdict that lied.\n\n## References\n\n\
         Each reference's own error is measured: how far its tip moves when it is extrapolated \
         from N and 2N rather than from N/2 and N, at every 1/{JUDGE_RATE} of a time unit (the \
         instants the choices are judged at), and at every 1/{REFERENCE_RATE}. `references.csv` gives each reference's tip and own error at every \
         1/{REFERENCE_ROWS_RATE} (every frame and every 1/{REFERENCE_RATE}).\n\n\
         | scene | method | N (runs at N/2, N, 2N) | observed order | own error at every 1/{JUDGE_RATE} | at every 1/{REFERENCE_RATE} |\n|---|---|---|---|---|---|\n",
        spec.duration,
        MethodKind::REFERENCE,
        spec.reference_segments,
        spec.reference_segments_max,
        spec.reference_segments_reach,
        spec.grid,
        spec.grid_beyond
    );
    for r in &checked.references {
        let (method, segments, order) = r.made_of();
        text += &format!(
            "| {} | {method} | {segments} | {order} | {:.1e} | {:.1e} |\n",
            r.scene(),
            r.own_error(),
            r.own_error_over(spec.duration, REFERENCE_RATE)
        );
    }
    text += "\n## Choices\n\n| scene | EPS | chosen (from) | true worst error | held | live estimate's bound at worst | verdict | CPU s (pilots + run) | grid's cheapest holding EPS | its worst error | its CPU s | ratio | notes |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    let run = |m: &Measured| format!("{} N = {}, k = {:.1e}", m.method, m.segments, m.dt);
    for c in &checked.cells {
        let chosen = c.chosen.as_ref();
        let cheapest = c.cheapest.as_ref();
        text += &format!(
            "| {} | {:.0e} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
            c.scene,
            c.tolerance,
            chosen.map_or("–".to_owned(), |m| format!(
                "{} ({})",
                run(m),
                c.basis.map_or("–", pilot::Basis::label)
            )),
            chosen.map_or("–".to_owned(), |m| format!("{:.1e}", m.worst)),
            match c.held() {
                Some(true) => "yes",
                Some(false) => "**no**",
                None => "–",
            },
            chosen
                .and_then(|m| m.estimate)
                .map_or("–".to_owned(), |e| format!("{e:.1e}")),
            c.verdict().map_or("–", EstimateVerdict::label),
            chosen.map_or("–".to_owned(), |m| format!(
                "{:.3} + {:.3}",
                c.pilot_seconds, m.seconds
            )),
            cheapest.map_or("none in the grid".to_owned(), run),
            cheapest.map_or("–".to_owned(), |m| format!("{:.1e}", m.worst)),
            cheapest.map_or("–".to_owned(), |m| format!("{:.3}", m.seconds)),
            c.cpu_ratio().map_or("–".to_owned(), |r| format!("{r:.1}")),
            c.skipped.as_deref().unwrap_or(""),
        );
    }
    text
}
