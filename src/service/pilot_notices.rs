//! What `--tolerance`'s pilots measured, as the run announces it: a line per method, from
//! the pilots' own estimates to the model fitted to them (or why a method was not flown).

use crate::methods::MethodKind;
use crate::plan::pilot::{self, Pilots};

/// What the pilots of `--tolerance` measured, a line per method.
pub fn pilot_lines(pilots: &Pilots, duration: f64) -> String {
    let seconds = pilots.seconds();
    let mut text = format!(
        "rope: tolerance pilots: to t = {}, {seconds:.2} s of CPU; the largest live tip estimate at each N flown:",
        duration.min(pilot::WINDOW)
    );
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
            (None, _, None) if !p.flew() => "not flown".to_owned(),
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
