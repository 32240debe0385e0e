//! `rope study --tolerance-check quick`, the small version CI runs: what `--tolerance` chooses
//! in two scenes, held against a converged reference at every frame.

use rope::Scene;
use rope::study::tolerance_check::{CheckSpec, REFERENCE_MARGIN, check};

#[test]
fn the_quick_tolerance_check_holds_eps_against_a_converged_reference_in_each_scene() {
    let spec = CheckSpec::quick();
    let checked = check(&spec, || {}).unwrap();
    let cells = &checked.cells;
    let eps = spec.tolerances[0];
    // The reference must be fine enough to judge EPS: the check says so when it is not.
    for r in &checked.references {
        eprintln!(
            "reference from the {}: order {:.2}, own error {:.1e}",
            r.scene, r.order, r.own_error
        );
        assert!(
            r.own_error <= REFERENCE_MARGIN * eps,
            "{}: own error {:.1e}",
            r.scene,
            r.own_error
        );
    }
    // Each reference starts where its scene does (y down): a release's tip at (cos θ, sin θ),
    // where every run starts too (its own error there is nil), a mode's hanging nearly
    // straight down.
    assert_eq!(checked.tips.len(), spec.scenes.len());
    for (scene, tip) in spec.scenes.iter().zip(&checked.tips) {
        let start = tip.at(0.0);
        if let Scene::Release { angle_deg } = *scene {
            let angle = angle_deg.to_radians();
            assert!((start.x - angle.cos()).abs() < 1e-12 && (start.y - angle.sin()).abs() < 1e-12);
            assert!(tip.own_error_at(0.0) < 1e-12);
        } else {
            assert!((start.y - 1.0).abs() < 1e-2, "{scene}: {start}");
        }
    }
    assert_eq!(cells.len(), spec.scenes.len());
    for cell in cells {
        assert!(cell.skipped.is_none(), "{}: {:?}", cell.scene, cell.skipped);
        let chosen = cell.chosen.expect("a chosen run that finished");
        eprintln!(
            "{}: {} at N = {}, worst tip error {:.1e}",
            cell.scene, chosen.method, chosen.segments, chosen.worst
        );
        assert_eq!(
            cell.held(),
            Some(true),
            "{}: {:.1e}",
            cell.scene,
            chosen.worst
        );
        // The grid has runs that hold EPS too: the comparison of CPU has something to compare.
        let cheapest = cell.cheapest.expect("a grid run that holds EPS");
        assert!(cheapest.worst <= eps);
    }
}
