//! The energy of the chain of rods, eq. (13) summed (eq. 16): from the rods' angles and
//! rates, or from unit tangents a method already holds at its angles. Segment i is a uniform
//! rod of mass m = h and length h; y points down, so the potential energy is −m g y.

use super::geometry::{length_of, tangent};
use nalgebra::Vector2;

/// Energy of the chain of rods (eq. 13 summed, eq. 16), in units of m g L.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Energy {
    /// Σ (m/2) v_i², the centres' motion.
    pub translational: f64,
    /// Σ (m h²/24) φ̇_i², each rod's spin about its centre.
    pub rotational: f64,
    /// Σ −m g y_i.
    pub potential: f64,
}

impl Energy {
    /// Translational plus rotational kinetic energy.
    pub fn kinetic(&self) -> f64 {
        self.translational + self.rotational
    }

    /// Kinetic plus potential energy: constant for the ideal string.
    pub fn total(&self) -> f64 {
        self.kinetic() + self.potential
    }
}

/// Energy of segments whose angle and angular velocity are given by `segment(i)`, in one
/// O(N) pass. The centre velocity is v_i = Σ_{m<i} h φ̇_m n_m + (h/2) φ̇_i n_i with the normal
/// n = (−sin φ, cos φ).
pub fn energy_of(n: usize, segment: impl Fn(usize) -> (f64, f64)) -> Energy {
    let h = 1.0 / n as f64;
    energy_of_rods(n, |i| {
        let (phi, omega) = segment(i);
        (phi, omega, h)
    })
}

/// As [`energy_of`], for rods of their own lengths (mass equal to length): `segment(i)` gives
/// rod i's angle, rate and length.
pub fn energy_of_rods(n: usize, segment: impl Fn(usize) -> (f64, f64, f64)) -> Energy {
    energy_along((0..n).map(|i| {
        let (phi, omega, h) = segment(i);
        (tangent(phi), omega, h)
    }))
}

/// As [`energy_of_rods`], for rods whose unit tangents are already known (a method that holds
/// them at its angles), turning at `rates`, of `lengths` (`None`: 1/N each): the same sum,
/// without a sine and cosine a rod.
pub fn energy_of_tangents(
    tangents: &[Vector2<f64>],
    rates: &[f64],
    lengths: Option<&[f64]>,
) -> Energy {
    let h = length_of(lengths, tangents.len());
    energy_along(
        tangents
            .iter()
            .zip(rates)
            .enumerate()
            .map(|(i, (&t, &omega))| (t, omega, h(i))),
    )
}

/// Eq. (13) summed over rods given support to tip as (unit tangent, rate, length).
fn energy_along(rods: impl Iterator<Item = (Vector2<f64>, f64, f64)>) -> Energy {
    let (mut p, mut v) = (Vector2::zeros(), Vector2::zeros());
    let mut e = Energy::default();
    for (t, omega, h) in rods {
        let m = h;
        let normal = Vector2::new(-t.y, t.x);
        let centre = p + 0.5 * h * t; // eqs. (14)–(15)
        let v_centre = v + 0.5 * h * omega * normal;
        e.translational += 0.5 * m * v_centre.norm_squared(); // eq. (13), first term
        e.rotational += m * h * h / 24.0 * omega * omega; // eq. (13), second term
        e.potential -= m * centre.y; // eq. (13), third term (y down)
        p += h * t;
        v += h * omega * normal;
    }
    e
}

/// Energy from angles and angular velocities at the same instant.
pub fn energy(angles: &[f64], angular_velocity: &[f64]) -> Energy {
    energy_of(angles.len(), |i| (angles[i], angular_velocity[i]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::geometry;

    #[test]
    fn hanging_string_at_rest_has_potential_minus_one_half() {
        let angles = vec![std::f64::consts::FRAC_PI_2; 10];
        let e = energy(&angles, &[0.0; 10]);
        assert!((e.potential + 0.5).abs() < 1e-12);
        assert_eq!(e.kinetic(), 0.0);
        assert!((geometry::tip(&angles) - geometry::Point::new(0.0, 1.0)).norm() < 1e-12);
    }

    #[test]
    fn rigid_rotation_has_the_kinetic_energy_of_a_rod_about_its_end() {
        // A straight string spinning at ω about the support: K = (1/2)(m L²/3) ω².
        let n = 50;
        let e = energy(&vec![0.3; n], &vec![2.0; n]);
        assert!((e.kinetic() - 0.5 / 3.0 * 4.0).abs() < 1e-12);
    }
}
