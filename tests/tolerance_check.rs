//! `rope study --tolerance-check quick`, the small version CI runs: what `--tolerance` chooses
//! in two scenes, held against a converged reference at every frame.

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
