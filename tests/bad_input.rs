//! Every bad parameter gets its own error, naming the parameter and what would work.

use rope::error::ConfigError;
use rope::methods::MethodKind;
use rope::model::Scene;
use rope::run::{RunConfig, RunPlan};

const THIRTY: Scene = Scene::Release { angle_deg: 30.0 };

fn config(
    method: MethodKind,
    scene: Scene,
    segments: usize,
    dt: Option<f64>,
) -> Result<RunPlan, ConfigError> {
    RunConfig {
        method,
        scene,
        segments,
        dt,
        duration: 1.0,
        ..RunConfig::default()
    }
    .validate()
}

/// The report's 30° release at N = 100, one time unit, default step: change one thing.
fn report() -> RunConfig {
    RunConfig {
        method: MethodKind::Seed,
        scene: THIRTY,
        segments: 100,
        duration: 1.0,
        ..RunConfig::default()
    }
}

#[test]
fn too_few_segments() {
    let err = config(MethodKind::Seed, THIRTY, 3, Some(1e-4)).unwrap_err();
    assert!(matches!(err, ConfigError::TooFewSegments { min: 4, .. }));
    assert!(err.to_string().starts_with("segments = 3"));
    assert!(matches!(
        config(MethodKind::Chain, THIRTY, 0, Some(1e-4)),
        Err(ConfigError::TooFewSegments { .. })
    ));
}

#[test]
fn time_step_zero_negative_or_not_finite() {
    for dt in [0.0, -1e-3, f64::NAN, f64::INFINITY] {
        let err = config(MethodKind::Seed, THIRTY, 100, Some(dt)).unwrap_err();
        assert!(matches!(err, ConfigError::TimeStep(_)), "{dt}: {err}");
        assert!(err.to_string().starts_with("dt = "));
    }
}

#[test]
fn time_step_past_the_seed_stability_limit() {
    let err = config(MethodKind::Seed, THIRTY, 100, Some(2e-2)).unwrap_err();
    assert!(matches!(err, ConfigError::UnstableTimeStep { .. }));
    assert!(err.to_string().contains("use dt ≤"), "{err}");
    // …unless asked for.
    assert!(
        RunConfig {
            dt: Some(2e-2),
            log_rate: 10.0,
            allow_unstable: true,
            ..report()
        }
        .validate()
        .is_ok()
    );
}

#[test]
fn duration_negative_or_nan_but_endless_is_fine() {
    for d in [-1.0, f64::NAN, f64::NEG_INFINITY] {
        let err = RunConfig {
            duration: d,
            ..report()
        }
        .validate()
        .unwrap_err();
        assert!(matches!(err, ConfigError::Duration(_)));
        assert!(err.to_string().starts_with("duration = "));
    }
    let endless = RunConfig {
        method: MethodKind::Chain,
        duration: f64::INFINITY,
        ..report()
    }
    .validate();
    assert!(endless.is_ok());
}

#[test]
fn angle_outside_zero_to_ninety_degrees() {
    for angle_deg in [-10.0, 90.5, f64::NAN] {
        let err = config(MethodKind::Chain, Scene::Release { angle_deg }, 100, None).unwrap_err();
        assert!(matches!(err, ConfigError::Angle(_)), "{angle_deg}");
    }
    let err = config(
        MethodKind::Chain,
        Scene::Release { angle_deg: -10.0 },
        100,
        None,
    )
    .unwrap_err();
    assert!(err.to_string().contains("compression"), "{err}");
}

#[test]
fn seed_scheme_from_the_horizontal_says_why_and_what_works() {
    let err = config(
        MethodKind::Seed,
        Scene::Release { angle_deg: 0.0 },
        100,
        None,
    )
    .unwrap_err();
    assert_eq!(err, ConfigError::SeedFromHorizontal);
    let text = err.to_string();
    assert!(text.contains("F_0") && text.contains("chain"), "{text}");
    // The chain starts there.
    assert!(
        config(
            MethodKind::Chain,
            Scene::Release { angle_deg: 0.0 },
            100,
            None
        )
        .is_ok()
    );
}

#[test]
fn mode_number_outside_one_to_four() {
    for number in [0, 5] {
        let err = config(
            MethodKind::Seed,
            Scene::Mode {
                number,
                amplitude: 0.05,
            },
            100,
            None,
        )
        .unwrap_err();
        assert_eq!(err, ConfigError::ModeNumber(number));
    }
}

#[test]
fn amplitude_too_large_or_not_finite() {
    for amplitude in [0.5, f64::NAN] {
        let err = config(
            MethodKind::Seed,
            Scene::Mode {
                number: 1,
                amplitude,
            },
            100,
            None,
        )
        .unwrap_err();
        assert!(matches!(err, ConfigError::Amplitude(_)));
    }
}

#[test]
fn log_rate_not_positive_or_above_the_step_rate() {
    let err = RunConfig {
        log_rate: 0.0,
        ..report()
    }
    .validate()
    .unwrap_err();
    assert!(matches!(err, ConfigError::LogRate(_)));
    let err = RunConfig {
        dt: Some(1e-2),
        log_rate: 1000.0,
        allow_unstable: true,
        ..report()
    }
    .validate()
    .unwrap_err();
    assert!(matches!(err, ConfigError::LogRateAboveSteps { .. }));
}

/// Too many frames for the step: the advice names a log rate and a step, and each works,
/// even where the step is longer than a time unit (a rate below 1).
#[test]
fn too_many_frames_for_the_step_advise_a_rate_and_a_step_that_work() {
    for (dt, log_rate) in [(1e-2, 1000.0), (10.0, 60.0), (3.0, 1.0), (0.7, 7.0)] {
        let asked = RunConfig {
            method: MethodKind::Midpoint,
            dt: Some(dt),
            log_rate,
            allow_unstable: true,
            ..report()
        };
        let Err(ConfigError::LogRateAboveSteps {
            most_frames,
            largest_dt,
            ..
        }) = asked.validate()
        else {
            panic!("k = {dt} at {log_rate} frames a time unit was not refused for its frames");
        };
        let rate: f64 = most_frames.parse().unwrap();
        let step: f64 = largest_dt.parse().unwrap();
        assert!(rate > 0.0 && step > 0.0, "{most_frames} {largest_dt}");
        let fewer = RunConfig {
            log_rate: rate,
            ..asked.clone()
        };
        assert!(
            fewer.validate().is_ok(),
            "--log-rate {most_frames} at k = {dt}"
        );
        let finer = RunConfig {
            dt: Some(step),
            ..asked
        };
        assert!(
            finer.validate().is_ok(),
            "--dt {largest_dt} at --log-rate {log_rate}"
        );
    }
}

#[test]
fn realtime_speed_not_positive() {
    let err = RunConfig {
        realtime: Some(0.0),
        ..report()
    }
    .validate()
    .unwrap_err();
    assert!(matches!(err, ConfigError::Realtime(_)));
}

#[test]
fn a_fold_gap_of_zero_negative_not_finite_or_past_two_over_pi() {
    for gap in [0.0, -0.01, f64::NAN, f64::INFINITY, 0.64, 1.0] {
        let err = config(MethodKind::Midpoint, Scene::Fold { gap }, 100, None).unwrap_err();
        assert!(matches!(err, ConfigError::FoldGap(_)), "{gap}: {err}");
        assert!(err.to_string().contains("gap"), "{err}");
    }
    assert!(config(MethodKind::Midpoint, Scene::Fold { gap: 0.63 }, 100, None).is_ok());
}

#[test]
fn seed_scheme_refuses_the_fold_saying_why_and_what_works() {
    let fold = Scene::Fold { gap: 0.04 };
    let err = config(MethodKind::Seed, fold, 100, None).unwrap_err();
    assert_eq!(err, ConfigError::SeedFold);
    let text = err.to_string();
    assert!(
        text.contains("tension") && text.contains("midpoint"),
        "{text}"
    );
    for method in [MethodKind::Chain, MethodKind::Rattle, MethodKind::Midpoint] {
        assert!(config(method, fold, 100, None).is_ok(), "{method}");
    }
}

#[test]
fn a_shake_of_no_negative_or_too_large_amplitude_or_frequency() {
    use rope::model::ShakeStart;
    let shake = |amplitude, frequency, start| Scene::Shake {
        amplitude,
        frequency,
        start,
    };
    for amplitude in [0.0, -1e-3, f64::NAN, 0.06] {
        let err = config(
            MethodKind::Midpoint,
            shake(amplitude, 2.0, ShakeStart::Steady),
            100,
            None,
        )
        .unwrap_err();
        assert!(
            matches!(err, ConfigError::ShakeAmplitude(_)),
            "{amplitude}: {err}"
        );
        assert!(err.to_string().starts_with("amplitude"), "{err}");
    }
    for frequency in [0.0, -2.0, f64::NAN, f64::INFINITY, 21.0] {
        let err = config(
            MethodKind::Midpoint,
            shake(1e-3, frequency, ShakeStart::Rest),
            100,
            None,
        )
        .unwrap_err();
        assert!(
            matches!(err, ConfigError::ShakeFrequency(_)),
            "{frequency}: {err}"
        );
        assert!(err.to_string().starts_with("frequency"), "{err}");
    }
    // On a resonance the steady state is unbounded: a steady start is refused, naming the
    // resonance and the start that shows it; from rest it runs.
    let err = config(
        MethodKind::Midpoint,
        shake(1e-2, 1.2024, ShakeStart::Steady),
        100,
        None,
    )
    .unwrap_err();
    let text = err.to_string();
    assert!(
        text.starts_with("frequency") && text.contains("1.2024") && text.contains("--from rest"),
        "{text}"
    );
    assert!(
        config(
            MethodKind::Midpoint,
            shake(1e-2, 1.2024, ShakeStart::Rest),
            100,
            None
        )
        .is_ok()
    );
    // Every rod method carries a moving support; the report's scheme refuses it.
    for method in [MethodKind::Chain, MethodKind::Rattle, MethodKind::Midpoint] {
        assert!(
            config(method, shake(1e-3, 2.0, ShakeStart::Steady), 100, None).is_ok(),
            "{method}"
        );
    }
    let err = config(
        MethodKind::Seed,
        shake(1e-3, 2.0, ShakeStart::Steady),
        100,
        None,
    )
    .unwrap_err();
    assert_eq!(err, ConfigError::SeedShake);
}

#[test]
fn graded_rods_refuse_every_scene_but_a_release_saying_what_works() {
    let mode = Scene::Mode {
        number: 1,
        amplitude: 0.05,
    };
    for scene in [mode, Scene::Fold { gap: 0.04 }] {
        let err = config(MethodKind::Graded, scene, 100, None).unwrap_err();
        let text = err.to_string();
        assert!(
            text.contains("graded") && text.contains("release") && text.contains("--method chain"),
            "{text}"
        );
    }
    assert!(config(MethodKind::Graded, THIRTY, 100, None).is_ok());
}
