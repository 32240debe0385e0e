//! How the worst tip error to t = 3 depends on the time step at fixed N: each rods method
//! (chain, rattle, midpoint), from each of five scenes, at N = 16, 32, 64 and 100, at its
//! default step and at 0.2, 0.5, 1 and 2 times its stability limit, against the chain
//! extrapolated from N = 200, 400 and 800. What each method's `tolerance_step_fraction` is
//! read from: a fraction whose worst error stays within 2.5 % of the default step's
//! everywhere. `scripts/tolerance-step.sh` runs it (about 3 minutes on 2 cores).

use rope::methods::MethodKind;
use rope::model::Scene;
use rope::plan::choice;
use rope::study::tip_reference::TipReference;
use rope::study::tolerance_check::measure;

/// The worst distance of the tip from the reference's over the frames (NaN if the run could
/// not start or diverged).
fn worst(method: MethodKind, scene: &Scene, n: usize, dt: f64, reference: &TipReference) -> f64 {
    measure(method, scene, n, dt, 3.0, None, reference).map_or(f64::NAN, |m| m.worst)
}

fn main() -> anyhow::Result<()> {
    let release = |angle_deg| Scene::Release { angle_deg };
    let mode = |number| Scene::Mode {
        number,
        amplitude: 0.05,
    };
    let scenes = [release(0.0), release(30.0), release(60.0), mode(1), mode(2)];
    let fractions = [0.2, 0.5, 1.0, 2.0];
    println!(
        "| scene | method | N | worst error at the default step | ratio at 0.2, 0.5, 1, 2 × the limit |"
    );
    println!("|---|---|---|---|---|");
    let mut largest = vec![[0f64; 4]; MethodKind::ALL.len()];
    for scene in &scenes {
        let reference = TipReference::compute(scene, 400, 3.0)?;
        eprintln!("{scene}: reference own error {:.1e}", reference.own_error);
        for method in choice::startable(scene, 3.0).filter(|m| *m != MethodKind::Seed) {
            let d = method.descriptor();
            for n in [16, 32, 64, 100] {
                let base = worst(method, scene, n, d.default_dt(n), &reference);
                let ratios = fractions
                    .map(|f| worst(method, scene, n, f * d.stability_limit(n), &reference) / base);
                let i = MethodKind::ALL
                    .iter()
                    .position(|m| *m == method)
                    .unwrap_or(0);
                for (l, r) in largest[i].iter_mut().zip(ratios) {
                    *l = l.max(r);
                }
                let text: Vec<String> = ratios.iter().map(|r| format!("{r:.3}")).collect();
                println!(
                    "| {scene} | {method} | {n} | {base:.3e} | {} |",
                    text.join(", ")
                );
            }
        }
    }
    println!("\nLargest ratio over scenes and N, at 0.2, 0.5, 1 and 2 × the limit:\n");
    for (method, l) in MethodKind::ALL.iter().zip(&largest) {
        if *method != MethodKind::Seed {
            println!(
                "- {method}: {:.3}, {:.3}, {:.3}, {:.3}",
                l[0], l[1], l[2], l[3]
            );
        }
    }
    Ok(())
}
