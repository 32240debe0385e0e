//! The linear theory of a mode's error (`rope::plan::mode_theory`) against the chain itself:
//! for modes 1 to 4 at tip amplitudes 0.05, 0.1 and 0.2, the chain's worst tip error at every
//! 1/3 000 of [0, T] (T = 3 and 10), at N = 4, 8, 16 and 32 at its tolerance step, against the
//! chain extrapolated from N = 100, 200 and 400, over what the theory predicts: where the
//! ratio stays near 1 the theory may stand for the pilots. Then what the theory costs to work
//! out at N = 32 … 512. About a minute on one core.

use rope::methods::MethodKind;
use rope::model::Scene;
use rope::plan::mode_theory;
use rope::study::tip_reference::TipReference;
use rope::study::tolerance_check::measure;
use std::time::Instant;

fn main() -> anyhow::Result<()> {
    println!(
        "| mode | tip amplitude | T | chain / theory at N = 4, 8, 16, 32 | chain's error at N = 32 |"
    );
    println!("|---|---|---|---|---|");
    for number in 1..=4 {
        for amplitude in [0.05, 0.1, 0.2] {
            let scene = Scene::Mode { number, amplitude };
            let reference = TipReference::compute(&scene, 100, 10.0)?;
            for duration in [3.0, 10.0] {
                let mut last = f64::NAN;
                let ratios: Vec<String> = [4, 8, 16, 32]
                    .into_iter()
                    .map(|n| {
                        let method = MethodKind::Chain;
                        let dt = method.tolerance_dt(n);
                        let chain = measure(method, &scene, n, dt, duration, None, &reference)
                            .map_or(f64::NAN, |m| m.worst);
                        let theory = mode_theory::tip_error(number, amplitude, n, duration)
                            .unwrap_or(f64::NAN);
                        last = chain;
                        format!("{:.2}", chain / theory)
                    })
                    .collect();
                println!(
                    "| {number} | {amplitude} | {duration} | {} | {last:.2e} (reference's own {:.0e}) |",
                    ratios.join(", "),
                    reference.own_error
                );
            }
        }
    }
    println!();
    println!("| N | the theory's error, mode 2, A = 0.05, T = 3 | ms to work it out |");
    println!("|---|---|---|");
    for n in [32, 64, 128, 256, 512] {
        let started = Instant::now();
        let error = mode_theory::tip_error(2, 0.05, n, 3.0).unwrap_or(f64::NAN);
        let ms = started.elapsed().as_secs_f64() * 1e3;
        println!("| {n} | {error:.3e} | {ms:.2} |");
    }
    Ok(())
}
