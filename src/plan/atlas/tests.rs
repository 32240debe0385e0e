//! The atlas's rules on small made-up atlases, and the committed ones read.

use super::*;

fn csv(rows: &[(&str, f64, [f64; SEGMENTS.len()])]) -> String {
    let mut text =
        "set,angle_deg,segments,worst,reference_segments,reference_own_error\n".to_owned();
    for (set, angle, errors) in rows {
        text += &row_against(set, *angle, errors, "0");
    }
    text
}

/// One angle's lines, every entry measured against a reference whose own error is `own` (as
/// written in the file).
fn row_against(set: &str, angle: f64, errors: &[f64; SEGMENTS.len()], own: &str) -> String {
    SEGMENTS
        .iter()
        .zip(errors)
        .map(|(n, e)| format!("{set},{angle},{n},{e:e},1600,{own}\n"))
        .collect()
}

/// Errors c/N at every N.
fn law(c: f64) -> [f64; SEGMENTS.len()] {
    SEGMENTS.map(|n| c / n as f64)
}

/// The atlas of errors 0.4/N at 0° and 0.2/N at 10°, and `held_out`/N at 5°: its margin
/// `held_out` / 0.4.
fn two_angles_and_5_degrees_held_out(held_out: f64) -> Atlas {
    let text = csv(&[
        ("atlas", 0.0, law(0.4)),
        ("atlas", 10.0, law(0.2)),
        ("held-out", 5.0, law(held_out)),
    ]);
    Atlas::parse(&text, WINDOW).expect("the atlas reads")
}

#[test]
fn the_committed_atlas_reads_and_its_margin_is_measured() {
    let atlas = Atlas::parse(CSV, WINDOW).expect("the committed atlas reads");
    assert_eq!(atlas.rows.len(), ATLAS_ANGLES.len());
    assert_eq!(atlas.held_out.len(), HELD_OUT_ANGLES.len());
    assert!(
        atlas.margin >= 1.0 && atlas.margin < 2.0,
        "{}",
        atlas.margin
    );
}

/// Measured at every 1/3 000 against the tolerance check's references, every chain row from
/// 20° to 80° is trusted to N = 566 (their own errors, 3.0e-6 to 2.1e-5 there, are far below
/// the chain's errors), and between any two of those angles the interpolated law serves 1e-3.
/// The vertical release's row is round-off; the references from 0° and 10° (the whips of the
/// chain at N = 3 200, extrapolated, err by 9.2e-4 and 2.8e-4 at every instant) cannot judge
/// 1e-3.
#[test]
fn the_committed_atlas_serves_1e_3_between_every_two_angles_from_20_to_80_degrees() {
    let atlas = Atlas::parse(CSV, WINDOW).expect("the committed atlas reads");
    for angle_deg in [23.0, 37.0, 44.0, 52.0, 58.0, 66.0, 77.0] {
        let model = atlas
            .interpolated(angle_deg, 1e-3)
            .unwrap_or_else(|| panic!("{angle_deg}°: the interpolated law does not serve 1e-3"));
        assert!(model.segments_for(1e-3) <= 566, "{angle_deg}°");
    }
    for (angle_deg, trusted) in atlas.rows() {
        let last = trusted.last().map_or(0, |&(n, _)| n);
        if (20.0..=80.0).contains(&angle_deg) {
            assert!(last >= 566, "{angle_deg}°: trusted to N = {last}");
        }
    }
    assert!(atlas.interpolated(12.0, 1e-3).is_none());
}

#[test]
fn the_committed_longer_graded_atlas_reads_from_40_degrees_and_serves_to_t_5_only() {
    let atlas = Atlas::committed_graded_longer().expect("it reads");
    let shorter = Atlas::committed_graded().expect("it reads");
    assert!(
        atlas.margin >= shorter.margin,
        "{} < {}",
        atlas.margin,
        shorter.margin
    );
    let angles = atlas
        .rows
        .iter()
        .chain(&atlas.held_out)
        .map(|r| r.angle_deg);
    assert!(
        angles.clone().all(|a| a >= LONGER_FROM),
        "{:?}",
        angles.collect::<Vec<_>>()
    );
    let release = Scene::Release { angle_deg: 45.0 };
    assert!(atlas.model(&release, LONGER_WINDOW, 1e-2).is_some());
    assert!(atlas.model(&release, LONGER_WINDOW + 0.1, 1e-2).is_none());
}

#[test]
fn the_committed_graded_atlas_reads_from_20_degrees_and_the_law_bounds_it() {
    let atlas = Atlas::parse(GRADED_CSV, WINDOW).expect("the committed graded atlas reads");
    assert!(atlas.rows.iter().all(|r| r.angle_deg >= GRADED_FROM));
    assert!(atlas.margin >= 1.0, "{}", atlas.margin);
    // It reaches 1e-4 from 20° to 60° (where the law asks N = 4 901), within the N it measured:
    // at 50° and 60° against the references refined to N = 25 600, which can judge 1e-4. Between
    // them too: the rows go on to N = 2 263, where every reference can judge 1e-4, and the
    // neighbours' law, their bound times the margin, reaches it there.
    for angle_deg in [20.0, 25.0, 30.0, 37.0, 40.0, 45.0, 50.0, 52.0, 55.0, 60.0] {
        let model = atlas
            .model(&Scene::Release { angle_deg }, 3.0, 1e-4)
            .unwrap_or_else(|| panic!("{angle_deg}°: no model at 1e-4"));
        assert!(model.segments_for(1e-4) <= 2263, "{angle_deg}°: {model:?}");
    }
    // The graded rods borrow the chain's one law: it bounds every trusted entry.
    let law = crate::plan::error_model::law(MethodKind::Graded);
    for (angle, points) in atlas.rows() {
        for (n, error) in points {
            assert!(error <= law.bound(n), "{angle}° at N = {n}: {error:e}");
        }
    }
}

/// The held-out rows are measurements at angles the atlas's rows do not include: wherever
/// the law interpolated from its neighbours claims to hold at a held-out angle, that
/// angle's own row must not show an error past the tolerance (at least: the measured error
/// less its reference's own). (The choice there is its own row's: this tests the law every
/// angle between two atlas angles gets.)
#[test]
fn the_interpolated_law_at_each_held_out_angle_holds_where_that_angle_was_measured() {
    for (name, text, window) in [
        ("chain", CSV, WINDOW),
        ("graded", GRADED_CSV, WINDOW),
        ("graded to t = 5", GRADED_LONGER_CSV, LONGER_WINDOW),
    ] {
        let atlas = Atlas::parse(text, window).expect("the committed atlas reads");
        for held in &atlas.held_out {
            for tolerance in [1e-2, 3e-3, 1e-3, 3e-4, 1e-4] {
                let Some(model) = atlas.interpolated(held.angle_deg, tolerance) else {
                    continue;
                };
                let chosen = model.segments_for(tolerance);
                for (j, n) in SEGMENTS.iter().enumerate() {
                    let at_least = held.floor(j).unwrap_or(0.0);
                    assert!(
                        *n < chosen || at_least <= tolerance,
                        "{name}, {}° at {tolerance:e}: N = {chosen} chosen, but at N = {n} \
                         the error is at least {at_least:.2e}",
                        held.angle_deg
                    );
                }
            }
        }
    }
}

#[test]
fn an_angle_between_two_takes_the_larger_error_and_the_held_out_margin() {
    let atlas = two_angles_and_5_degrees_held_out(0.5);
    assert!((atlas.margin - 1.25).abs() < 1e-12);
    let model = atlas
        .model(&Scene::Release { angle_deg: 7.0 }, 3.0, 1e-3)
        .unwrap();
    // 0.4 × 1.25 / 1e-3 = 500 segments.
    assert_eq!(model.segments_for(1e-3), 500);
    // Past the atlas's N, in a mode, or past its window: no model.
    assert!(
        atlas
            .model(&Scene::Release { angle_deg: 7.0 }, 3.0, 1e-4)
            .is_none()
    );
    assert!(
        atlas
            .model(&Scene::Release { angle_deg: 7.0 }, 3.5, 1e-3)
            .is_none()
    );
    let mode = Scene::Mode {
        number: 1,
        amplitude: 0.05,
    };
    assert!(atlas.model(&mode, 3.0, 1e-3).is_none());
}

#[test]
fn at_an_atlas_angle_the_fewest_measured_n_whose_bound_holds_is_chosen_without_the_margin() {
    let atlas = two_angles_and_5_degrees_held_out(0.8);
    assert!((atlas.margin - 2.0).abs() < 1e-12);
    let at = |angle_deg, eps| {
        let model = atlas.model(&Scene::Release { angle_deg }, 3.0, eps)?;
        Some(model.segments_for(eps))
    };
    // At 10°, 0.2/N is within 1e-3 from N = 200, which the atlas measured; the law times
    // the margin would ask for 400.
    assert_eq!(at(10.0, 1e-3), Some(200));
    // Within 1.5e-3 from N = 133.3: the next measured, 141 (the law times the margin: 267).
    assert_eq!(at(10.0, 1.5e-3), Some(141));
    // Where the law times the margin asks fewer than the next measured N, the law: with no
    // held-out angle (a margin of 1), 1e-2 from 0.2/N asks for 20, where the next measured
    // N is 25.
    let no_margin = Atlas::parse(
        &csv(&[("atlas", 0.0, law(0.4)), ("atlas", 10.0, law(0.2))]),
        WINDOW,
    )
    .unwrap();
    let model = no_margin.model(&Scene::Release { angle_deg: 10.0 }, 3.0, 1e-2);
    assert_eq!(model.map(|m| m.segments_for(1e-2)), Some(20));
    // Between two atlas angles, the margin: 0.4 × 2 / 1e-3.
    assert_eq!(at(7.0, 1e-3), Some(800));
    // At 0°, 0.4/N is within 1e-4 only from N = 4 000, past what was measured: no model.
    assert_eq!(at(0.0, 1e-4), None);
}

#[test]
fn at_a_held_out_angle_its_own_row_is_chosen_without_the_margin() {
    // 5° errs by 0.2/N, below its neighbours' 0.4/N; 15° by 0.4/N, twice theirs (0.2/N):
    // the margin is 2.
    let text = csv(&[
        ("atlas", 0.0, law(0.4)),
        ("atlas", 10.0, law(0.2)),
        ("atlas", 20.0, law(0.2)),
        ("held-out", 5.0, law(0.2)),
        ("held-out", 15.0, law(0.4)),
    ]);
    let atlas = Atlas::parse(&text, WINDOW).unwrap();
    assert!((atlas.margin - 2.0).abs() < 1e-12);
    let at = |angle_deg: f64| {
        let model = atlas.model(&Scene::Release { angle_deg }, 3.0, 1e-3)?;
        Some(model.segments_for(1e-3))
    };
    // At 5° its own 0.2/N holds 1e-3 from N = 200; the law from 0° and 10° with the margin
    // would ask 0.4 × 2 / 1e-3 = 800. A hair off it, the law or the envelope: 0.4/N (0° and
    // 15°, neither above the other: its margin is 1) holds 1e-3 from 400.
    assert_eq!(at(5.0), Some(200));
    let law_there = atlas.interpolated(5.5, 1e-3).map(|m| m.segments_for(1e-3));
    assert_eq!(law_there, Some(800));
    assert_eq!(atlas.envelope_margin, 1.0);
    assert_eq!(at(5.5), Some(400));
    // At 15° its own 0.4/N asks 400 (the next measured N past 400: 400 itself); the law
    // from 10° and 20° with the margin the same, 0.2 × 2 / 1e-3 = 400.
    assert_eq!(at(15.0), Some(400));
}

#[test]
fn an_untrusted_held_out_error_still_raises_the_margin_by_what_it_is_at_least() {
    let mut text = csv(&[("atlas", 0.0, law(0.4)), ("atlas", 10.0, law(0.2))]);
    // The 5° row errs by 0.4/N, but at N = 566 by 0.9/N against a reference whose own
    // error is 2e-4 (untrusted): the error there is at least (0.9/566 − 2e-4), 1.97 times
    // its neighbours'.
    for (n, e) in SEGMENTS.iter().zip(law(0.4)) {
        let (e, own) = match *n == 566 {
            true => (0.9 / 566.0, 2e-4),
            false => (e, 0.0),
        };
        text += &format!("held-out,5,{n},{e:e},1600,{own:e}\n");
    }
    let atlas = Atlas::parse(&text, WINDOW).unwrap();
    let expected = (0.9 / 566.0 - 2e-4) / (0.4 / 566.0);
    assert!((atlas.margin - expected).abs() < 1e-9, "{}", atlas.margin);
    // An entry that errs by less than its reference's own says nothing.
    let quiet = text.replace(
        &format!("{:e},1600,{:e}", 0.9 / 566.0, 2e-4),
        "1e-4,1600,2e-4",
    );
    assert_eq!(Atlas::parse(&quiet, WINDOW).unwrap().margin, 1.0);
}

#[test]
fn a_constant_that_falls_with_n_is_used_only_from_where_it_falls() {
    // 0.4/N up to N = 100, then 0.2/N: 1e-3 needs N = 200 from the smaller constant
    // (0.2 / 1e-3), though 0.2 / 1.2e-3 alone would ask for 167 < 200 … from N = 141 up.
    let mut errors = law(0.4);
    for (e, n) in errors.iter_mut().zip(SEGMENTS) {
        if n >= 141 {
            *e = 0.2 / n as f64;
        }
    }
    let atlas = Atlas::parse(
        &csv(&[("atlas", 0.0, errors), ("atlas", 10.0, errors)]),
        WINDOW,
    )
    .unwrap();
    let at = |eps| {
        atlas
            .model(&Scene::Release { angle_deg: 0.0 }, 3.0, eps)
            .unwrap()
            .segments_for(eps)
    };
    assert_eq!(at(1e-3), 200);
    // 1.6e-3 would need 125 by the smaller constant: it bounds only from 141 up.
    assert_eq!(at(1.6e-3), 141);
    // 1e-2: 40 by the larger constant, which bounds every N.
    assert_eq!(at(1e-2), 40);
}

#[test]
fn an_entry_whose_reference_cannot_judge_the_tolerance_ends_the_row_for_it() {
    let mut text = csv(&[("atlas", 10.0, law(0.2))]);
    // The 0° row: its reference's own error 1e-3, above a tenth of every error past N = 50.
    text += &row_against("atlas", 0.0, &law(0.5), "1e-3");
    let atlas = Atlas::parse(&text, WINDOW).unwrap();
    let release = Scene::Release { angle_deg: 0.0 };
    // 2e-2 it can judge (1e-3 ≤ 2e-3), but the bounds past N = 50, 0.5/N + 1e-3, carry the
    // reference's error, whose constant grows with N (3.7 at 3 200): the law from the trusted
    // ones, to N = 50, asks 28 (its constant 0.55, at 50).
    assert_eq!(
        atlas.model(&release, 3.0, 2e-2).unwrap().segments_for(2e-2),
        28
    );
    // 5e-3 it cannot: the law reads only the trusted entries, to N = 50, which do not reach it.
    assert!(atlas.model(&release, 3.0, 5e-3).is_none());
}

#[test]
fn an_entry_too_coarse_for_the_margin_still_bounds_what_its_reference_can_judge() {
    // 10° errs by 0.1/N against a reference whose own error is 9e-6: from N = 1131 (8.8e-5)
    // the entries are below ten times it, so the margin would not read them. They still bound
    // the error, 0.1/N + 9e-6, for a tolerance the reference could judge (1e-4: 9e-6 ≤ 1e-5).
    let mut text = csv(&[("atlas", 0.0, law(0.1))]);
    text += &row_against("atlas", 10.0, &law(0.1), "9e-6");
    let atlas = Atlas::parse(&text, WINDOW).unwrap();
    let at = |angle_deg, eps| {
        let model = atlas.model(&Scene::Release { angle_deg }, 3.0, eps)?;
        Some(model.segments_for(eps))
    };
    // Its own row bounds the error at 1131 by 9.7e-5; the law, from the bounds at 800 and 1131
    // around it (the larger constant 0.1 + 9e-6 × 1131), asks 1102.
    assert_eq!(
        atlas.measured(10.0, 1e-4).map(|m| m.segments_for(1e-4)),
        Some(1131)
    );
    assert_eq!(at(10.0, 1e-4), Some(1102));
    // So between 0° and 10°: 10°'s bounds are the larger.
    assert_eq!(at(5.0, 1e-4), Some(1102));
    // A reference that could not judge 1e-4 (own error 1.1e-5) serves it nowhere: neither its
    // own row, nor the law past N = 800 (1.25e-4), nor the envelope.
    let coarse = Atlas::parse(&text.replace(",9e-6", ",1.1e-5"), WINDOW).unwrap();
    for angle_deg in [5.0, 10.0] {
        let model = coarse.model(&Scene::Release { angle_deg }, 3.0, 1e-4);
        assert!(model.is_none(), "{angle_deg}°: {model:?}");
    }
}

/// Errors 0.1/N from 0°, 15° (held out) and, but at N = 1131, where they dip to 0.01/N, from
/// 10° and 20°: the neighbours' margin is 10 (15° against 10° and 20° at N = 1131), the
/// envelope's 1 (no angle strays above every other).
fn a_dip_at_1131() -> Atlas {
    let mut dipping = law(0.1);
    dipping[SEGMENTS.iter().position(|&n| n == 1131).unwrap()] = 0.01 / 1131.0;
    let text = csv(&[
        ("atlas", 0.0, law(0.1)),
        ("atlas", 10.0, dipping),
        ("atlas", 20.0, dipping),
        ("held-out", 15.0, law(0.1)),
    ]);
    Atlas::parse(&text, WINDOW).unwrap()
}

#[test]
fn an_unseen_angle_takes_the_envelope_of_every_angle_where_its_neighbours_dip_together() {
    let atlas = a_dip_at_1131();
    assert!((atlas.margin - 10.0).abs() < 1e-9, "{}", atlas.margin);
    assert_eq!(atlas.envelope_margin, 1.0);
    let at = |angle_deg, eps| {
        let model = atlas.model(&Scene::Release { angle_deg }, 3.0, eps)?;
        Some(model.segments_for(eps))
    };
    // At 12°, the envelope 0.1/N holds 1e-3 from N = 100; the neighbours' law, 0.1 × 10 /
    // 1e-3, would ask 1000.
    assert_eq!(
        atlas.enveloped(12.0, 1e-3).map(|m| m.segments_for(1e-3)),
        Some(100)
    );
    assert_eq!(
        atlas.interpolated(12.0, 1e-3).map(|m| m.segments_for(1e-3)),
        Some(1000)
    );
    assert_eq!(at(12.0, 1e-3), Some(100));
    // 1e-4 from N = 1131, where the envelope (0° and 15°) is 8.8e-5.
    assert_eq!(at(12.0, 1e-4), Some(1131));
    // Outside the atlas's angles, nothing.
    assert_eq!(at(25.0, 1e-3), None);
}

#[test]
fn the_envelope_margin_is_how_far_one_angle_strays_above_all_the_others() {
    // 20° errs by 0.15/N at N = 200, 1.5 times every other angle there.
    let mut straying = law(0.1);
    straying[SEGMENTS.iter().position(|&n| n == 200).unwrap()] = 0.15 / 200.0;
    let text = csv(&[
        ("atlas", 0.0, law(0.1)),
        ("atlas", 10.0, law(0.1)),
        ("atlas", 20.0, straying),
    ]);
    let atlas = Atlas::parse(&text, WINDOW).unwrap();
    assert!((atlas.envelope_margin - 1.5).abs() < 1e-9);
    // 0.1/N × 1.5 holds 1e-3 from N = 150, but at N = 200 the envelope is 20°'s 0.15/200:
    // × 1.5, 1.1e-3. So N = 283.
    let model = atlas.enveloped(5.0, 1e-3).unwrap();
    assert_eq!(model.segments_for(1e-3), 283);
}

#[test]
fn the_envelope_serves_only_where_every_angle_was_measured_against_a_reference_that_could_judge() {
    let mut text = csv(&[("atlas", 0.0, law(0.1)), ("held-out", 15.0, law(0.1))]);
    // 10°, unmeasured at N = 100 and measured at 141 against a reference whose own error,
    // 2e-4, could not judge 1e-3 (a tenth of it at most).
    for (n, e) in SEGMENTS.iter().zip(law(0.1)) {
        match n {
            100 => {}
            141 => text += &format!("atlas,10,{n},{e:e},1600,2e-4\n"),
            _ => text += &format!("atlas,10,{n},{e:e},1600,0\n"),
        }
    }
    text += &row_against("atlas", 20.0, &law(0.1), "0");
    let atlas = Atlas::parse(&text, WINDOW).unwrap();
    let model = atlas.enveloped(12.0, 1e-3).unwrap();
    assert_eq!(model.segments_for(1e-3), 200);
    // 2e-2 may be judged against it: from N = 141 (0.1/141 + 2e-4 = 9.1e-4 ≤ 2e-2… but at
    // N = 16, 6.3e-3, already).
    assert_eq!(atlas.enveloped(12.0, 2e-2).unwrap().segments_for(2e-2), 16);
}
