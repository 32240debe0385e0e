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
