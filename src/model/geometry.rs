//! From angles to positions and energy: the report's eqs. (13)–(16), with the recursive form
//! of (17)–(18) done as one running sum (its printed typos corrected: `docs/physics.md`).
//!
//! Segment i is a uniform rod of mass m = h and length h from node i to node i + 1; node 0 is
//! the support at the origin. y points down, so the potential energy is −m g y.

use nalgebra::{Point2, Vector2};

/// A point in the plane of the swing (x away from the support, y down).
pub type Point = Point2<f64>;

/// Unit tangent of a segment at angle φ below the horizontal.
#[inline]
pub fn tangent(angle: f64) -> Vector2<f64> {
    let (s, c) = angle.sin_cos();
    Vector2::new(c, s)
}

/// The unit tangent `tangent` = (cos θ, sin θ) turned by `delta`: (cos, sin) of θ + δ. Where
/// |δ| < 0.1 (a rod's turn within a step) the sine and cosine of δ are their Taylor series to
/// δ¹⁰, whose truncation (below 3e-19) is under round-off; otherwise the library's.
#[inline]
pub fn turned(tangent: Vector2<f64>, delta: f64) -> Vector2<f64> {
    let (s, c) = if delta.abs() < 0.1 {
        // Multiplied by reciprocals (a division each would cost more than the rest).
        let x = |k: f64| delta * delta * (1.0 / k);
        let s = delta * (1.0 - x(6.0) * (1.0 - x(20.0) * (1.0 - x(42.0) * (1.0 - x(72.0)))));
        let c =
            1.0 - x(2.0) * (1.0 - x(12.0) * (1.0 - x(30.0) * (1.0 - x(56.0) * (1.0 - x(90.0)))));
        (s, c)
    } else {
        delta.sin_cos()
    };
    Vector2::new(tangent.x * c - tangent.y * s, tangent.y * c + tangent.x * s)
}

/// Node positions, support … tip: N + 1 points (eqs. 14–15 at the segment ends).
pub fn nodes(angles: &[f64], out: &mut Vec<Point>) {
    let h = 1.0 / angles.len() as f64;
    out.clear();
    let mut p = Point::origin();
    out.push(p);
    for &phi in angles {
        p += h * tangent(phi);
        out.push(p);
    }
}

/// Segment centres (eqs. 14–15): x_i = Σ_{m<i} h cos φ_m + (h/2) cos φ_i, y likewise.
pub fn centres(angles: &[f64], out: &mut Vec<Point>) {
    let h = 1.0 / angles.len() as f64;
    out.clear();
    let mut p = Point::origin();
    for &phi in angles {
        let t = tangent(phi);
        out.push(p + 0.5 * h * t);
        p += h * t;
    }
}

/// The point at arc length `s` (0 at the support, 1 at the tip) along the equal segments
/// between `nodes` (support … tip).
pub fn at_arc_length(nodes: &[Point], s: f64) -> Point {
    let segments = nodes.len().saturating_sub(1);
    if segments == 0 {
        return nodes.first().copied().unwrap_or_else(Point::origin);
    }
    let x = s * segments as f64;
    let i = (x.floor() as usize).min(segments - 1);
    let frac = x - i as f64;
    nodes[i] + frac * (nodes[i + 1] - nodes[i])
}

/// The largest distance between two strings at equal arc length, over the nodes of the finer
/// (`a` and `b` are node lists, support … tip, of any two segment counts).
pub fn largest_distance(a: &[Point], b: &[Point]) -> f64 {
    let points = a.len().max(b.len()).max(2);
    (0..points)
        .map(|j| {
            let s = j as f64 / (points - 1) as f64;
            (at_arc_length(a, s) - at_arc_length(b, s)).norm()
        })
        .fold(0.0, f64::max)
}

/// The tip (free end) position.
pub fn tip(angles: &[f64]) -> Point {
    let h = 1.0 / angles.len() as f64;
    angles
        .iter()
        .fold(Point::origin(), |p, &phi| p + h * tangent(phi))
}

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
    let (mut p, mut v) = (Vector2::zeros(), Vector2::zeros());
    let mut e = Energy::default();
    for i in 0..n {
        let (phi, omega, h) = segment(i);
        let m = h;
        let (s, c) = phi.sin_cos();
        let t = Vector2::new(c, s);
        let normal = Vector2::new(-s, c);
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

/// Tip velocity Σ h φ̇_i n_i.
pub fn tip_velocity(angles: &[f64], angular_velocity: &[f64]) -> Vector2<f64> {
    let h = 1.0 / angles.len() as f64;
    angles
        .iter()
        .zip(angular_velocity)
        .fold(Vector2::zeros(), |v, (&phi, &w)| {
            let (s, c) = phi.sin_cos();
            v + h * w * Vector2::new(-s, c)
        })
}

/// The string's momentum (mass 1): Σ m_i v_i over the rods' centres, = Σ h φ̇_j n_j (1 − s_j),
/// s_j = (j + ½) h, since rod j's turn moves every centre beyond it and its own by half.
pub fn momentum(angles: &[f64], angular_velocity: &[f64]) -> Vector2<f64> {
    let h = 1.0 / angles.len() as f64;
    angles
        .iter()
        .zip(angular_velocity)
        .enumerate()
        .fold(Vector2::zeros(), |p, (j, (&phi, &w))| {
            let (s, c) = phi.sin_cos();
            let beyond = 1.0 - (j as f64 + 0.5) * h;
            p + h * w * beyond * Vector2::new(-s, c)
        })
}

/// The string's first moment Σ m_i c_i (mass 1) over the rods' centres, = Σ h t_j (1 − s_j),
/// s_j = (j + ½) h, as for [`momentum`]: the centre of mass. Under a shaken support the
/// frame's inertial force does work on its sideways part.
pub fn first_moment(angles: &[f64]) -> Vector2<f64> {
    let h = 1.0 / angles.len() as f64;
    angles
        .iter()
        .enumerate()
        .fold(Vector2::zeros(), |x, (j, &phi)| {
            let beyond = 1.0 - (j as f64 + 0.5) * h;
            x + h * beyond * tangent(phi)
        })
}

/// The rods' centre velocities v_i = Σ_{j<i} h φ̇_j n_j + (h/2) φ̇_i n_i of equal rods at
/// `angles` turning at `angular_velocity`: what a method in maximal coordinates starts from.
pub fn centre_velocities(angles: &[f64], angular_velocity: &[f64]) -> Vec<Vector2<f64>> {
    let h = 1.0 / angles.len() as f64;
    let mut end = Vector2::zeros();
    angles
        .iter()
        .zip(angular_velocity)
        .map(|(&phi, &w)| {
            let (s, c) = phi.sin_cos();
            let turn = h * w * Vector2::new(-s, c);
            let centre = end + 0.5 * turn;
            end += turn;
            centre
        })
        .collect()
}

/// Tip acceleration Σ h (φ̈_i n_i − φ̇_i² t_i).
pub fn tip_acceleration(
    angles: &[f64],
    angular_velocity: &[f64],
    angular_acceleration: &[f64],
) -> Vector2<f64> {
    let h = 1.0 / angles.len() as f64;
    let mut a = Vector2::zeros();
    for ((&phi, &w), &alpha) in angles
        .iter()
        .zip(angular_velocity)
        .zip(angular_acceleration)
    {
        let (s, c) = phi.sin_cos();
        a += h * (alpha * Vector2::new(-s, c) - w * w * Vector2::new(c, s));
    }
    a
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tangent_turned_by_a_small_angle_is_the_tangent_at_the_sum() {
        // Across the series' range and past it, at angles of every quadrant: within a few
        // ulps of the library's sine and cosine of θ + δ.
        for theta in [-2.9, -0.7, 0.0, 0.4, 1.3, 2.2, 3.1, 7.5] {
            for delta in [
                0.0, 1e-9, -3e-5, 0.002, -0.02, 0.0999, -0.0999, 0.1, 0.35, -1.2,
            ] {
                let got = turned(tangent(theta), delta);
                let want = tangent(theta + delta);
                assert!(
                    (got - want).norm() < 1e-15,
                    "θ = {theta}, δ = {delta}: {got:?} against {want:?}"
                );
            }
        }
    }

    #[test]
    fn a_point_along_the_string_is_found_by_arc_length() {
        let nodes = [
            Point::new(0.0, 0.0),
            Point::new(0.5, 0.0),
            Point::new(0.5, 0.5),
        ];
        assert_eq!(at_arc_length(&nodes, 0.0), nodes[0]);
        assert_eq!(at_arc_length(&nodes, 0.25), Point::new(0.25, 0.0));
        assert_eq!(at_arc_length(&nodes, 0.75), Point::new(0.5, 0.25));
        assert_eq!(at_arc_length(&nodes, 1.0), nodes[2]);
    }

    #[test]
    fn largest_distance_is_at_equal_arc_length_whatever_the_segment_counts() {
        // A straight string along x against one bent down at its middle, at 2 and 4 segments.
        let straight = [0.0, 0.25, 0.5, 0.75, 1.0].map(|x| Point::new(x, 0.0));
        let bent = [
            Point::new(0.0, 0.0),
            Point::new(0.5, 0.0),
            Point::new(0.5, 0.5),
        ];
        // At the tip (s = 1): (1, 0) against (0.5, 0.5).
        let tip_gap = (0.5f64 * 0.5 + 0.5 * 0.5).sqrt();
        assert!((largest_distance(&straight, &bent) - tip_gap).abs() < 1e-15);
        assert_eq!(largest_distance(&straight, &straight), 0.0);
    }

    #[test]
    fn hanging_string_at_rest_has_potential_minus_one_half() {
        let angles = vec![std::f64::consts::FRAC_PI_2; 10];
        let e = energy(&angles, &[0.0; 10]);
        assert!((e.potential + 0.5).abs() < 1e-12);
        assert_eq!(e.kinetic(), 0.0);
        assert!((tip(&angles) - Point::new(0.0, 1.0)).norm() < 1e-12);
    }

    #[test]
    fn rigid_rotation_has_the_kinetic_energy_of_a_rod_about_its_end() {
        // A straight string spinning at ω about the support: K = (1/2)(m L²/3) ω².
        let n = 50;
        let e = energy(&vec![0.3; n], &vec![2.0; n]);
        assert!((e.kinetic() - 0.5 / 3.0 * 4.0).abs() < 1e-12);
    }
}
