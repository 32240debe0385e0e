//! What a sweep of the shaken support's frequency says when it ends: a line per resonance
//! of linear theory, with the peaks it found there, and where its chart went.

use super::notices::{Notice, Topic};
use crate::model::bessel::mode_frequency;
use crate::model::scene::resonance_number;

/// What a sweep from `span.0` to `span.1` found: for each resonance ω_n the tallest peak
/// nearest it of the free end's largest swing (`largest`) and of its swing at Ω alone
/// (`driven`); a resonance inside the sweep that its grid shows no peak at, with a finer grid
/// to try. Then its CPU time and where its chart went (`chart`: written there, or not asked
/// for, or why it could not be written).
pub fn sweep(
    span: (f64, f64),
    frequencies: usize,
    largest: &[(f64, f64)],
    driven: &[(f64, f64)],
    cpu_seconds: f64,
    chart: Result<Option<&std::path::Path>, String>,
) -> Notice {
    let (largest, driven) = (tallest_peaks(largest), tallest_peaks(driven));
    let mut lines = vec![format!(
        "rope: sweep of {frequencies} frequencies from Ω = {} to {} in {cpu_seconds:.1} s of CPU simulating",
        span.0, span.1
    )];
    let mut numbers: Vec<u32> = largest.iter().chain(&driven).map(|p| p.0).collect();
    numbers.extend((1..=resonances_below(span.1)).filter(|&n| inside(span, n)));
    numbers.sort_unstable();
    numbers.dedup();
    for n in numbers {
        let resonance = mode_frequency(n);
        let at = |peaks: &[(u32, f64)]| peaks.iter().find(|p| p.0 == n).map(|p| p.1);
        let (swing, alone) = (at(&largest), at(&driven));
        let (lo, hi) = (0.95 * resonance, 1.05 * resonance);
        let finer = format!("--sweep {lo:.2}..{hi:.2}:41");
        let said = |what: &str, peak: Option<f64>| match peak {
            Some(omega) => format!(
                "{what} peaks at Ω = {omega:.4} ({:+.2} %)",
                100.0 * (omega / resonance - 1.0)
            ),
            None => format!("{what} shows no peak near it"),
        };
        // Beyond 5 % of ω_n the grid, not the string, places the peak.
        let placed =
            |peak: Option<f64>| peak.is_some_and(|omega| (omega / resonance - 1.0).abs() <= 0.05);
        let line = match (swing, alone) {
            (None, None) => format!(
                "rope: ω{n} = {resonance:.4} lies inside the sweep, but its grid shows no peak near it; a finer grid may ({finer})"
            ),
            _ => format!(
                "rope: ω{n} = {resonance:.4}: {}, {}{}",
                said("the largest swing", swing),
                said("the swing at Ω alone", alone),
                match placed(swing) && placed(alone) {
                    true => String::new(),
                    false => format!("; the grid is too coarse to place it ({finer})"),
                }
            ),
        };
        lines.push(line);
    }
    lines.push(match chart {
        Ok(Some(path)) => format!(
            "rope: the sweep's chart and table: {}.png, .svg, .csv",
            path.display()
        ),
        Ok(None) => {
            "rope: give --save FILE.rrd to keep the sweep's chart and table beside the recording"
                .to_owned()
        }
        Err(why) => {
            format!("rope: the sweep's chart could not be written ({why}); the recording is whole")
        }
    });
    Notice::new(Topic::Sweep, lines.join("\n"))
}

/// How many resonances lie at or below `frequency`.
fn resonances_below(frequency: f64) -> u32 {
    (1..)
        .take_while(|&n| mode_frequency(n) <= frequency)
        .count() as u32
}

/// Whether ω_n lies strictly inside the sweep `span`.
fn inside(span: (f64, f64), n: u32) -> bool {
    let resonance = mode_frequency(n);
    span.0 < resonance && resonance < span.1
}

/// The tallest of `peaks` nearer each resonance than any other (a start from rest adds
/// smaller peaks of its free modes between them): its resonance's number and its Ω.
fn tallest_peaks(peaks: &[(f64, f64)]) -> Vec<(u32, f64)> {
    let mut tallest: Vec<(u32, f64, f64)> = Vec::new();
    for &(omega, swing) in peaks {
        let n = resonance_number(omega);
        match tallest.iter_mut().find(|t| t.0 == n) {
            Some(t) if swing > t.2 => *t = (n, omega, swing),
            Some(_) => {}
            None => tallest.push((n, omega, swing)),
        }
    }
    tallest
        .into_iter()
        .map(|(n, omega, _)| (n, omega))
        .collect()
}
