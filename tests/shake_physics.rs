//! The hanging string whose support is shaken sideways, x_s = A sin Ωt, against the linear
//! theory of D. Bernoulli's string (`rope::model::support::steady_response`): started on the
//! steady state off resonance the motion stays periodic at the free-end amplitude A/|J₀(2Ω)|;
//! from rest at the first resonance the amplitude grows in proportion to time; and the energy
//! balance E − E₀ − W closes. N = 100, A = 1e-3.

mod common;

use common::*;
use rope::methods::MethodKind;
use rope::model::bessel;
use rope::model::support::{resonant_growth_per_period, steady_response};
use rope::model::{Scene, ShakeStart};
use rope::run::Frame;
use rope::run::shake_figures::{ShakeFigures, ShakeSample};

const SEGMENTS: usize = 100;
const AMPLITUDE: f64 = 1e-3;

fn shake(frequency: f64, start: ShakeStart) -> Scene {
    Scene::Shake {
        amplitude: AMPLITUDE,
        frequency,
        start,
    }
}

/// `method`'s frames of `scene` at 100 frames per time unit to `duration`.
fn frames(method: MethodKind, scene: Scene, duration: f64) -> Vec<Frame> {
    let dt = method.default_dt(SEGMENTS);
    let (outcome, frames) = run_frames(method, scene, SEGMENTS, dt, duration, 100.0);
    assert!(outcome.diverged.is_none(), "{:?}", outcome.diverged);
    frames
}

/// The largest sideways excursion of the free end in the room over `frames`.
fn tip_amplitude<'a>(frames: impl IntoIterator<Item = &'a Frame>) -> f64 {
    frames
        .into_iter()
        .map(|f| f.tip().x.abs())
        .fold(0.0, f64::max)
}

#[test]
fn started_on_the_steady_state_off_resonance_the_free_end_swings_a_over_j0_for_twenty_periods() {
    for frequency in [0.6, 2.0] {
        let periods = 20.0;
        let duration = periods * std::f64::consts::TAU / frequency;
        let frames = frames(
            MethodKind::Midpoint,
            shake(frequency, ShakeStart::Steady),
            duration,
        );
        let predicted = AMPLITUDE * steady_response(frequency, 0.0).abs();
        let measured = tip_amplitude(&frames);
        let off = measured / predicted - 1.0;
        eprintln!(
            "shake Ω = {frequency}: free end's amplitude {measured:.5e} over {periods} periods, A/|J0(2Ω)| = {predicted:.5e}, off by {:.3} %",
            100.0 * off
        );
        assert!(off.abs() < 0.01, "Ω = {frequency}: off by {off:.3e}");
        // The swing at Ω alone (the summary's lock-in reading) is the steady state's too.
        let mut figures = None;
        for f in &frames {
            let support = f.support.expect("a shaken support");
            let sample = ShakeSample {
                time: f.time,
                tip_x: f.tip().x,
                balance: f.balance.expect("a shake's balance"),
                work: support.work,
            };
            ShakeFigures::push(&mut figures, shake(frequency, ShakeStart::Steady), sample);
        }
        let driven = figures.expect("a shake's figures").driven_amplitude;
        eprintln!("shake Ω = {frequency}: at Ω alone {driven:.5e}");
        assert!(
            (driven / predicted - 1.0).abs() < 0.01,
            "Ω = {frequency}: at Ω alone {driven:.5e} against {predicted:.5e}"
        );
        // Periodic: the last period's amplitude is the first one's (no growing free mode).
        let per_period = frames.len() / periods as usize;
        let (first, last) = (
            tip_amplitude(&frames[..per_period]),
            tip_amplitude(&frames[frames.len() - per_period..]),
        );
        assert!(
            (last / first - 1.0).abs() < 0.01,
            "Ω = {frequency}: first period {first:.4e}, last {last:.4e}"
        );
        // In step with the support below ω₁, against it between ω₁ and ω₂.
        let in_step = frames
            .iter()
            .map(|f| f.tip().x * f.support.expect("a moving support").position)
            .sum::<f64>();
        assert_eq!(in_step > 0.0, frequency < bessel::mode_frequency(1));
    }
}

#[test]
fn shaken_from_rest_at_the_first_resonance_the_amplitude_grows_in_proportion_to_time() {
    let omega_1 = bessel::mode_frequency(1);
    let period = std::f64::consts::TAU / omega_1;
    let frames = frames(
        MethodKind::Midpoint,
        shake(omega_1, ShakeStart::Rest),
        16.0 * period,
    );
    // The free end's amplitude over each period.
    let per_period = frames.len() / 16;
    let amplitudes: Vec<f64> = frames
        .chunks(per_period)
        .take(16)
        .map(tip_amplitude)
        .collect();
    // Undamped resonance: u ∝ t sin ωt, so the amplitude gains the same each period. Its
    // growth from period 4 to 8 and from 8 to 16 agree, and it has grown far past the
    // steady state of any frequency a few per cent away.
    let gain = |a: usize, b: usize| (amplitudes[b] - amplitudes[a]) / (b - a) as f64;
    let (early, late) = (gain(3, 7), gain(7, 15));
    let theory = resonant_growth_per_period(1, AMPLITUDE);
    eprintln!(
        "shake from rest at ω1: amplitude per period {amplitudes:.4?}; gain per period {early:.4e} (periods 4–8), {late:.4e} (8–16); linear theory 2πA/(j J1(j)) = {theory:.4e}"
    );
    for gain in [early, late] {
        assert!(
            (gain / theory - 1.0).abs() < 0.02,
            "gain per period {gain:.4e} against {theory:.4e}"
        );
    }
    assert!(amplitudes[15] > 3.0 * amplitudes[3]);
}

#[test]
fn the_energy_balance_closes_to_round_off_for_midpoint_and_to_its_order_for_the_others() {
    // Driven at resonance the support pumps energy in: E − E₀ grows by W.
    let omega_1 = bessel::mode_frequency(1);
    let duration = 10.0 * std::f64::consts::TAU / omega_1;
    for (method, bound) in [
        (MethodKind::Midpoint, 1e-9),
        (MethodKind::Rattle, 1e-6),
        (MethodKind::Chain, 1e-6),
    ] {
        let frames = frames(method, shake(omega_1, ShakeStart::Rest), duration);
        let worst = frames
            .iter()
            .map(|f| f.balance.expect("a moving support's balance").abs())
            .fold(0.0, f64::max);
        let work = frames
            .last()
            .and_then(|f| f.support)
            .expect("a moving support")
            .work;
        let gained = frames.last().expect("frames").energy.total() - frames[0].energy.total();
        eprintln!(
            "shake from rest at ω1, {method}: |E − E0 − W| ≤ {worst:.2e} at every frame; W = {work:.3e}, E − E0 = {gained:.3e} at the end"
        );
        assert!(worst <= bound, "{method}: balance {worst:.3e}");
        // The support's work is the energy gained, and far above the balance's residue.
        assert!(work > 1e4 * worst.max(1e-12), "{method}: work {work:.3e}");
        assert!(
            (gained / work - 1.0).abs() < 1e-3,
            "{method}: {gained:.3e} vs {work:.3e}"
        );
    }
}

#[test]
fn the_seed_scheme_refuses_a_moving_support_and_names_the_methods_that_carry_one() {
    let err = MethodKind::Seed
        .build(&shake(2.0, ShakeStart::Steady), SEGMENTS, 1e-3)
        .err()
        .expect("the seed refuses");
    let text = err.to_string();
    assert!(
        text.contains("moving support") && text.contains("midpoint"),
        "{text}"
    );
}
