//! What a sweep of the shaken support's frequency says when it ends: the peaks it found
//! against the resonances of linear theory.

use super::notices::{Notice, Topic};

/// What a sweep of the shaken support's frequency found: the peaks of the free end's largest
/// swing and of its swing at Ω alone against the resonances ω_n of linear theory, its CPU
/// time, and where its chart went (`chart`: written there, or not asked for, or why it could
/// not be written).
pub fn sweep(
    frequencies: usize,
    largest: &[(f64, f64)],
    driven: &[(f64, f64)],
    cpu_seconds: f64,
    chart: Result<Option<&std::path::Path>, String>,
) -> Notice {
    let found = format!(
        "the tallest peak nearest each resonance of the free end's largest swing at {}; of its swing at Ω alone at {}",
        tallest_peaks(largest),
        tallest_peaks(driven)
    );
    let kept = match chart {
        Ok(Some(path)) => format!("its chart and CSV: {}.png, .svg, .csv", path.display()),
        Ok(None) => {
            "give --save FILE.rrd to keep its chart and CSV beside the recording".to_owned()
        }
        Err(why) => format!("its chart could not be written ({why}); the recording is whole"),
    };
    Notice::new(
        Topic::Sweep,
        format!(
            "rope: sweep of {frequencies} frequencies in {cpu_seconds:.1} s of CPU simulating: {found}; {kept}"
        ),
    )
}

/// The tallest of `peaks` nearer each resonance than any other (a start from rest adds
/// smaller peaks of its free modes between them), each against its ω_n, in words.
fn tallest_peaks(peaks: &[(f64, f64)]) -> String {
    let mut tallest: Vec<(u32, f64, f64)> = Vec::new();
    for &(omega, swing) in peaks {
        let n = crate::model::scene::resonance_number(omega);
        match tallest.iter_mut().find(|t| t.0 == n) {
            Some(t) if swing > t.2 => *t = (n, omega, swing),
            Some(_) => {}
            None => tallest.push((n, omega, swing)),
        }
    }
    if tallest.is_empty() {
        return "none within the sweep".to_owned();
    }
    let named: Vec<String> = tallest
        .iter()
        .map(|&(n, omega, _)| {
            let resonance = crate::model::bessel::mode_frequency(n);
            format!(
                "Ω = {omega:.4} (ω{n} = {resonance:.4}: {:+.2} %)",
                100.0 * (omega / resonance - 1.0)
            )
        })
        .collect();
    named.join(", ")
}
