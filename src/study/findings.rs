//! What the study's rows say: convergence orders, the stability limit against N, and the
//! cheapest run that reaches the report's accuracy.

use super::charts::measured_boundary;
use super::grid::{Row, Status, fit};
use super::reference::Reference;
use crate::methods::Descriptor;
use crate::methods::{MethodKind, REPORT};
use crate::plan::error_model::ErrorModel;
use std::fmt::Write as _;

/// Everything the study concludes, as numbers and as text.
#[derive(Clone, Debug)]
pub struct Findings {
    pub tip_models: Vec<(MethodKind, ErrorModel)>,
    pub energy_models: Vec<(MethodKind, ErrorModel)>,
    pub boundaries: Vec<(MethodKind, Vec<(f64, f64)>)>,
    /// The report's run, and the cheapest run at least as accurate (tip and energy).
    pub report_run: Option<Row>,
    pub cheapest: Option<Row>,
    /// The report's method's cheapest run within 10 % of its best tip error, and each other
    /// method's cheapest run at least as accurate.
    pub report_method_best: Option<Row>,
    pub matching: Vec<Row>,
    /// Each method's cheapest run with a tip error at most [`TIP_TARGET`].
    pub at_target: Vec<Row>,
    /// The grid's coarse edges: its fewest segments and its longest step. A cheapest run on
    /// one of them may have a cheaper one beyond it, outside the grid.
    pub coarse_edges: (usize, f64),
}

/// The tip error at which the methods' costs are compared side by side.
pub const TIP_TARGET: f64 = 1e-4;

/// Energy deviation as the "error" of a fit (same fitting code, other metric).
fn energy_rows(rows: &[Row]) -> Vec<Row> {
    rows.iter()
        .map(|r| Row {
            tip_error: r.energy_deviation,
            ..r.clone()
        })
        .collect()
}

impl Findings {
    /// Reads the rows. Fits use N ≥ 20 (the asymptotic range).
    pub fn from_rows(rows: &[Row]) -> Self {
        let methods: Vec<MethodKind> = MethodKind::ALL
            .into_iter()
            .filter(|m| {
                rows.iter()
                    .any(|r| r.method == *m && r.status == Status::Ok)
            })
            .collect();
        let energy = energy_rows(rows);
        let report_run = rows
            .iter()
            .find(|r| {
                r.method == REPORT.method
                    && r.segments == REPORT.segments
                    && (r.dt / REPORT.dt - 1.0).abs() < 1e-9
                    && r.status == Status::Ok
            })
            .cloned();
        let cheapest = report_run.as_ref().and_then(|report| {
            let (tip, energy) = (report.tip_error?, report.energy_deviation?);
            rows.iter()
                .filter(|r| r.status == Status::Ok)
                .filter(|r| r.tip_error.is_some_and(|e| e <= tip))
                .filter(|r| r.energy_deviation.is_some_and(|e| e <= energy))
                .min_by(|a, b| a.cpu_seconds.total_cmp(&b.cpu_seconds))
                .cloned()
        });
        let report_method_best = best_of(rows, REPORT.method);
        let matching = report_method_best
            .as_ref()
            .and_then(|best| best.tip_error)
            .map(|target| {
                MethodKind::ALL
                    .into_iter()
                    .filter(|&m| m != REPORT.method)
                    .filter_map(|m| cheapest_within(rows, m, target))
                    .collect()
            })
            .unwrap_or_default();
        let at_target = methods
            .iter()
            .filter_map(|&m| cheapest_within(rows, m, TIP_TARGET))
            .collect();
        let fewest = rows.iter().map(|r| r.segments).min().unwrap_or(0);
        let longest = rows.iter().map(|r| r.dt).fold(0.0, f64::max);
        Self {
            report_method_best,
            matching,
            at_target,
            coarse_edges: (fewest, longest),
            tip_models: methods
                .iter()
                .filter_map(|&m| Some((m, fit(rows, m, 20)?)))
                .collect(),
            energy_models: methods
                .iter()
                .filter_map(|&m| Some((m, fit(&energy, m, 20)?)))
                .collect(),
            boundaries: methods
                .iter()
                .map(|&m| (m, measured_boundary(rows, m)))
                .collect(),
            report_run,
            cheapest,
        }
    }

    /// The findings as Markdown, with the reference's own error estimate first.
    pub fn markdown(&self, reference: &Reference, command: &str) -> String {
        let mut s = format!("# Study findings\n\nMade by `{command}`.\n\n");
        s += &format!(
            "Reference: {}. Estimated error of the reference tip, the largest over the frames: {:.1e} from N, {:.1e} from k; tip errors below {:.1e} are not resolved. A run's tip error is the largest over its frames ({} a time unit), each against the reference at that frame's time; `study.csv` also keeps the error at the final time alone (`final_tip_error`).\n\n",
            reference.description,
            reference.error_in_h,
            reference.error_in_k,
            reference.error_estimate(),
            super::grid::FRAMES_PER_UNIT,
        );
        s += &self.convergence_section();
        s += &self.stability_section();
        s += &self.against_report_method_section();
        s += &self.report_accuracy_section();
        s += &self.at_target_section();
        s
    }

    /// Each method's cheapest run to a tip error of [`TIP_TARGET`], against the cheapest.
    fn at_target_section(&self) -> String {
        let Some(least) = self
            .at_target
            .iter()
            .map(|r| r.cpu_seconds)
            .min_by(f64::total_cmp)
        else {
            return String::new();
        };
        let mut s = format!(
            "\n## A tip error of {TIP_TARGET:.0e}: each method's cheapest run\n\n| method | N | k | tip error | CPU s | × the cheapest | at the grid's edge |\n|---|---|---|---|---|---|---|\n"
        );
        for r in &self.at_target {
            let _ = writeln!(
                s,
                "| {} | {} | {:.3e} | {:.2e} | {:.2e} | {:.2} | {} |",
                r.method,
                r.segments,
                r.dt,
                r.tip_error.unwrap_or(f64::NAN),
                r.cpu_seconds,
                r.cpu_seconds / least.max(1e-12),
                self.edge(r).map_or(String::new(), |e| format!("**{e}**"))
            );
        }
        if self.at_target.iter().any(|r| self.edge(r).is_some()) {
            s += "\nA run at the grid's edge (its fewest N or its longest k) may not be the cheapest: a cheaper one that holds the target may lie beyond the grid. Widen the grid there to know.\n";
        }
        s
    }

    /// Which coarse edge of the grid `r` sits on, if any: there a cheaper run may lie beyond.
    pub fn edge(&self, r: &Row) -> Option<String> {
        let (fewest, longest) = self.coarse_edges;
        let mut on = Vec::new();
        if r.segments == fewest {
            on.push(format!("fewest N ({fewest})"));
        }
        if r.dt == longest {
            on.push(format!("longest k ({longest:e})"));
        }
        (!on.is_empty()).then(|| on.join(", "))
    }

    /// Fitted orders in h, for the tip error and the energy deviation.
    fn convergence_section(&self) -> String {
        let mut s = String::from(
            "## Convergence in h (least-squares fit over N ≥ 20, smallest stable k)\n\n| method | tip error ≈ C h^p | energy deviation ≈ C h^p |\n|---|---|---|\n",
        );
        for (m, tip) in &self.tip_models {
            let energy = self
                .energy_models
                .iter()
                .find(|(e, _)| e == m)
                .map(|(_, e)| {
                    let note = if e.order < 0.5 {
                        " (not an h-error: set by k)"
                    } else {
                        ""
                    };
                    format!("{:.3e} h^{:.2}{note}", e.constant, e.order)
                })
                .unwrap_or_default();
            let _ = writeln!(
                s,
                "| {m} | {:.3e} h^{:.2} | {energy} |",
                tip.constant, tip.order
            );
        }
        let unfitted: Vec<String> = self
            .boundaries
            .iter()
            .map(|(m, _)| *m)
            .filter(|m| !self.tip_models.iter().any(|(fitted, _)| fitted == m))
            .map(|m| m.to_string())
            .collect();
        if !unfitted.is_empty() {
            let _ = writeln!(
                s,
                "\nNo fit for {}: a fit needs stable runs at two or more N ≥ 20, with a tip error above the reference's; add larger --segments (e.g. 20,40,80).",
                unfitted.join(", ")
            );
        }
        s
    }

    /// The measured stability boundary of each method, with its Courant number.
    fn stability_section(&self) -> String {
        let mut s = String::from(
            "\n## Stability: largest stable k against N (geometric mean of the last ok and first diverged k)\n\n",
        );
        for (m, boundary) in &self.boundaries {
            if boundary.is_empty() {
                let _ = writeln!(s, "- {m}: no run diverged anywhere on the grid.");
                continue;
            }
            let points: Vec<String> = boundary
                .iter()
                .map(|&(n, k)| {
                    let c = Descriptor::courant_of(n, k);
                    format!("N = {n}: k ≈ {k:.1e} (C = k·N·sqrt(F_max) ≈ {c:.2})")
                })
                .collect();
            let _ = writeln!(s, "- {m}: {}", points.join("; "));
        }
        s
    }

    /// What every other method costs to reach the report's method's best tip error.
    fn against_report_method_section(&self) -> String {
        let Some(best) = &self.report_method_best else {
            return String::new();
        };
        let mut s = String::new();
        for other in &self.matching {
            let _ = writeln!(
                s,
                "\n## {} against {}\n\nThe {} method's best tip error on the grid, {:.2e}, costs it {:.2e} CPU s at the least (N = {}, k = {:.3e}). The {} method reaches it (tip error {:.2e}) with N = {}, k = {:.3e} in {:.2e} CPU s: **{}**.",
                other.method,
                best.method,
                best.method,
                best.tip_error.unwrap_or(f64::NAN),
                best.cpu_seconds,
                best.segments,
                best.dt,
                other.method,
                other.tip_error.unwrap_or(f64::NAN),
                other.segments,
                other.dt,
                other.cpu_seconds,
                compared(best.cpu_seconds, other.cpu_seconds)
            );
        }
        s
    }

    /// The report's run against the cheapest run at least as accurate.
    fn report_accuracy_section(&self) -> String {
        let (Some(report), Some(best)) = (&self.report_run, &self.cheapest) else {
            return String::new();
        };
        format!(
            "\n## The report's accuracy for less\n\nThe report's run ({}, N = {}, k = {:e}): tip error {:.2e}, energy deviation {:.2e}, {:.3} CPU s.\nThe cheapest run at least as accurate in both: {} N = {}, k = {:.3e}: tip error {:.2e}, energy deviation {:.2e}, {:.2e} CPU s, **{}**.\n",
            REPORT.method,
            REPORT.segments,
            REPORT.dt,
            report.tip_error.unwrap_or(f64::NAN),
            report.energy_deviation.unwrap_or(f64::NAN),
            report.cpu_seconds,
            best.method,
            best.segments,
            best.dt,
            best.tip_error.unwrap_or(f64::NAN),
            best.energy_deviation.unwrap_or(f64::NAN),
            best.cpu_seconds,
            compared(report.cpu_seconds, best.cpu_seconds)
        )
    }
}

/// How a run's CPU time `other` compares with `base`'s, in words that say "more" when it is
/// more: "112× less CPU", "1.9× more CPU".
fn compared(base: f64, other: f64) -> String {
    let (ratio, word) = if other <= base {
        (base / other.max(1e-12), "less")
    } else {
        (other / base.max(1e-12), "more")
    };
    if ratio >= 10.0 {
        format!("{ratio:.0}× {word} CPU")
    } else {
        format!("{ratio:.2}× {word} CPU")
    }
}

/// The ok runs of `method`.
fn ok_runs(rows: &[Row], method: MethodKind) -> impl Iterator<Item = &Row> {
    rows.iter()
        .filter(move |r| r.method == method && r.status == Status::Ok)
}

/// The cheapest run of `method` with a tip error at most `target`.
fn cheapest_within(rows: &[Row], method: MethodKind, target: f64) -> Option<Row> {
    ok_runs(rows, method)
        .filter(|r| r.tip_error.is_some_and(|e| e <= target))
        .min_by(|a, b| a.cpu_seconds.total_cmp(&b.cpu_seconds))
        .cloned()
}

/// The cheapest run of `method` within 10 % of its smallest tip error on the grid (time steps
/// change a first-order method's error by less than that, so those runs count as reaching it).
fn best_of(rows: &[Row], method: MethodKind) -> Option<Row> {
    let best = ok_runs(rows, method)
        .filter_map(|r| r.tip_error)
        .min_by(f64::total_cmp)?;
    cheapest_within(rows, method, best * 1.1)
}

#[cfg(test)]
mod tests {
    use super::compared;

    #[test]
    fn a_run_that_costs_more_is_said_to_cost_more() {
        assert_eq!(compared(1.0, 3.9), "3.90× more CPU");
        assert_eq!(compared(1.0, 1.9), "1.90× more CPU");
        assert_eq!(compared(112.0, 1.0), "112× less CPU");
        assert_eq!(compared(2.0, 1.0), "2.00× less CPU");
    }
}
