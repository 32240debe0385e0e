//! The support the string hangs from: fixed, or shaken sideways, x_s(t) = A sin Ωt. The rod
//! methods step the string in the support's frame, where a moving support is a gravity that
//! changes with time, g(t) = (−ẍ_s(t), g) (y down); this module gives that gravity, the
//! support's motion in the room, and the bookkeeping of the work the support does, W(t) =
//! ∫ F_support · v_s dt, so that E(t) − E(0) − W(t) can be watched (docs/physics.md, "The
//! shaken support").

use super::bessel;
use super::energy::Energy;
use nalgebra::Vector2;

/// How the support moves.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Support {
    /// Held still at the origin.
    #[default]
    Fixed,
    /// Moved sideways, x_s(t) = `amplitude` sin(`frequency` t), in string lengths and radians
    /// per time unit.
    Shaken { amplitude: f64, frequency: f64 },
}

impl Support {
    /// x_s(t), the support's sideways position in the room.
    pub fn position(&self, time: f64) -> f64 {
        match *self {
            Self::Fixed => 0.0,
            Self::Shaken {
                amplitude,
                frequency,
            } => amplitude * (frequency * time).sin(),
        }
    }

    /// ẋ_s(t).
    pub fn velocity(&self, time: f64) -> f64 {
        match *self {
            Self::Fixed => 0.0,
            Self::Shaken {
                amplitude,
                frequency,
            } => amplitude * frequency * (frequency * time).cos(),
        }
    }

    /// ẍ_s(t).
    pub fn acceleration(&self, time: f64) -> f64 {
        match *self {
            Self::Fixed => 0.0,
            Self::Shaken {
                amplitude,
                frequency,
            } => -amplitude * frequency * frequency * (frequency * time).sin(),
        }
    }

    /// Gravity in the support's frame at time `time`, per unit mass (y down): (−ẍ_s, 1). The
    /// frame's acceleration acts on every rod as a uniform force, so it enters the equations
    /// exactly where gravity does.
    pub fn gravity(&self, time: f64) -> Vector2<f64> {
        Vector2::new(-self.acceleration(time), 1.0)
    }

    /// Whether the support moves at all: a method pays for the bookkeeping only then.
    pub fn moves(&self) -> bool {
        !matches!(self, Self::Fixed)
    }
}

/// The linear steady state of a string whose support is shaken at `frequency` (Ω), at the
/// height `z` = 1 − s above the free end: its sideways displacement over the support's
/// amplitude, u/A = J₀(2Ω√z) / J₀(2Ω), in phase with the support. Infinite at a resonance,
/// J₀(2Ω) = 0.
pub fn steady_response(frequency: f64, z: f64) -> f64 {
    bessel::j0(2.0 * frequency * z.max(0.0).sqrt()) / bessel::j0(2.0 * frequency)
}

/// The free end's swing in the linear steady state of a support shaken with `amplitude` at
/// `frequency`: A/|J₀(2Ω)|.
pub fn free_end_swing(amplitude: f64, frequency: f64) -> f64 {
    amplitude * steady_response(frequency, 0.0).abs()
}

/// How much the free end's amplitude grows each period when a string at rest is shaken at
/// its `n`-th resonance ω_n with amplitude `amplitude`, by linear theory. The n-th mode's
/// share of the frame's uniform inertial force is c_n = ∫J₀(2ω_n√z) dz / ∫J₀²(2ω_n√z) dz =
/// 2/(j J₁(j)), j = 2ω_n, so its amplitude obeys q̈ + ω_n² q = c_n A ω_n² sin ω_n t, whose
/// resonant answer grows as c_n A ω_n t/2: c_n π A a period, at the free end where the mode
/// is 1.
pub fn resonant_growth_per_period(n: u32, amplitude: f64) -> f64 {
    let j = bessel::j0_zero(n);
    2.0 / (j * bessel::j1(j)) * std::f64::consts::PI * amplitude
}

/// The support, as a method stepping in the support's frame sees it, and the work it has done
/// since the start. With X the string's first moment Σ m x (mass 1) and P′ its sideways
/// momentum in the support's frame, the support's sideways force is the rate of change of the
/// string's sideways momentum in the room, P′ + ẋ_s, so by parts
///
/// W(t) = [ẋ_s P′ + ẋ_s²/2]₀ᵗ − ∫ ẍ_s dX,
///
/// the integral summed step by step as ẍ_s(t_mid) ΔX: the work the frame's inertial force does
/// in the discrete equations of a method that evaluates it at each step's middle.
#[derive(Clone, Copy, Debug, Default)]
pub struct SupportLedger {
    support: Support,
    /// Σ ẍ_s(t_mid) ΔX over the steps taken.
    inertial: f64,
    /// ẋ_s P′ + ẋ_s²/2 at the start.
    start: f64,
}

/// A moving support at one instant, for output: where it is in the room, how it moves, and
/// the work it has done on the string since the start.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SupportNow {
    pub position: f64,
    pub velocity: f64,
    pub acceleration: f64,
    /// W(t).
    pub work: f64,
}

impl SupportNow {
    /// What carries the string's points from the support's frame into the room, sideways.
    pub fn offset(&self) -> Vector2<f64> {
        Vector2::new(self.position, 0.0)
    }
}

/// The free end of rods at `angles` (of `lengths` where they are not all 1/N) in the room,
/// hanging from `support` (if it moves).
pub fn tip_in_the_room(
    support: Option<SupportNow>,
    angles: &[f64],
    lengths: Option<&[f64]>,
) -> super::geometry::Point {
    point_in_the_room(support, super::geometry::tip_of(angles, lengths))
}

/// A point drawn from the support (a method's [`tip`](crate::methods::Method::tip)) in the
/// room, where `support` (if it moves) is.
pub fn point_in_the_room(
    support: Option<SupportNow>,
    point: super::geometry::Point,
) -> super::geometry::Point {
    let mut points = [point];
    into_the_room(support, &mut points);
    points[0]
}

/// Carries `points` drawn from the support into the room, where `support` (if it moves) is.
pub fn into_the_room(support: Option<SupportNow>, points: &mut [super::geometry::Point]) {
    if let Some(s) = support {
        points.iter_mut().for_each(|p| *p += s.offset());
    }
}

impl SupportLedger {
    /// The ledger of `support` for a string starting with sideways momentum `momentum_x` in
    /// the support's frame.
    pub fn new(support: Support, momentum_x: f64) -> Self {
        let v = support.velocity(0.0);
        Self {
            support,
            inertial: 0.0,
            start: v * momentum_x + 0.5 * v * v,
        }
    }

    /// Whether the support moves at all.
    pub fn moves(&self) -> bool {
        self.support.moves()
    }

    /// Gravity in the support's frame at `time` ([`Support::gravity`]).
    pub fn gravity(&self, time: f64) -> Vector2<f64> {
        self.support.gravity(time)
    }

    /// After a step from `start` of length `dt` that moved the first moment X by `moved`.
    pub fn step(&mut self, start: f64, dt: f64, moved: f64) {
        if self.moves() {
            self.inertial += self.support.acceleration(start + 0.5 * dt) * moved;
        }
    }

    /// Σ ẍ_s(t_mid) ΔX so far: the support's frame's inertial force's work, with its sign
    /// turned (what the energy in the support's frame has lost to it).
    pub fn inertial_work(&self) -> f64 {
        self.inertial
    }

    /// The support at `time`, for a string whose sideways momentum in the support's frame
    /// `momentum_x` gives (asked only where the support moves); `None` for a fixed support.
    pub fn now(&self, time: f64, momentum_x: impl FnOnce() -> f64) -> Option<SupportNow> {
        if !self.moves() {
            return None;
        }
        let v = self.support.velocity(time);
        Some(SupportNow {
            position: self.support.position(time),
            velocity: v,
            acceleration: self.support.acceleration(time),
            work: v * momentum_x() + 0.5 * v * v - self.start - self.inertial,
        })
    }

    /// The energy in the room from `frame`, the energy in the support's frame at `time`, of a
    /// string whose sideways momentum there `momentum_x` gives (mass 1; asked only where the
    /// support moves): the translational part gains ẋ_s P′ + ẋ_s²/2.
    pub fn in_the_room(
        &self,
        frame: Energy,
        time: f64,
        momentum_x: impl FnOnce() -> f64,
    ) -> Energy {
        if !self.moves() {
            return frame;
        }
        let v = self.support.velocity(time);
        Energy {
            translational: frame.translational + v * momentum_x() + 0.5 * v * v,
            ..frame
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_fixed_support_does_no_work_and_adds_nothing_to_the_energy() {
        let mut ledger = SupportLedger::new(Support::Fixed, 0.3);
        ledger.step(0.0, 0.1, 0.2);
        assert_eq!(ledger.now(1.0, || 0.5), None);
        let e = Energy {
            translational: 0.25,
            rotational: 0.01,
            potential: -0.5,
        };
        assert_eq!(ledger.in_the_room(e, 1.0, || 0.5).total(), e.total());
        assert_eq!(Support::Fixed.gravity(2.0), Vector2::new(0.0, 1.0));
    }

    #[test]
    fn a_shaken_support_s_motion_is_a_sine_and_its_gravity_leans_against_it() {
        let support = Support::Shaken {
            amplitude: 0.01,
            frequency: 2.0,
        };
        let t = 0.3;
        // Derivatives by central differences.
        let d = 1e-5;
        let v = (support.position(t + d) - support.position(t - d)) / (2.0 * d);
        let a = (support.velocity(t + d) - support.velocity(t - d)) / (2.0 * d);
        assert!((v - support.velocity(t)).abs() < 1e-10);
        assert!((a - support.acceleration(t)).abs() < 1e-10);
        assert_eq!(support.gravity(t).x, -support.acceleration(t));
    }

    #[test]
    fn the_steady_response_is_one_at_the_support_and_grows_towards_a_resonance() {
        assert!((steady_response(0.6, 1.0) - 1.0).abs() < 1e-15);
        let omega_1 = bessel::mode_frequency(1);
        assert!(steady_response(0.999 * omega_1, 0.0) > 100.0);
    }

    #[test]
    fn a_string_carried_along_rigidly_takes_the_support_s_work_as_its_kinetic_energy() {
        // A string at rest in the support's frame (P' = 0, X fixed): the room's energy gains
        // v_s²/2 (mass 1), and the ledger says the support did exactly that.
        let support = Support::Shaken {
            amplitude: 0.02,
            frequency: 1.5,
        };
        let ledger = SupportLedger::new(support, 0.0);
        let t = 0.7;
        let e = ledger.in_the_room(Energy::default(), t, || 0.0);
        let w = ledger.now(t, || 0.0).expect("a moving support").work;
        let (v0, v) = (support.velocity(0.0), support.velocity(t));
        assert!((w - (v * v - v0 * v0) / 2.0).abs() < 1e-15);
        assert!((e.total() - v * v / 2.0).abs() < 1e-15);
    }
}
