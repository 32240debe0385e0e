//! From angles to positions: the report's eqs. (14)–(16), with the recursive form of (17)–(18)
//! done as one running sum (its printed typos corrected: `docs/physics.md`); the energy of
//! eq. (13) is in [`super::energy`].
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
    nodes_of(angles, None, out);
}

/// The rods' lengths: each its own where `lengths` gives them (graded rods), else 1/N.
#[inline]
pub(super) fn length_of(lengths: Option<&[f64]>, segments: usize) -> impl Fn(usize) -> f64 + '_ {
    let h = 1.0 / segments as f64;
    move |i| lengths.map_or(h, |l| l[i])
}

/// As [`nodes`], for rods of the lengths `lengths` where they are given (graded rods), of
/// length 1/N each where not.
pub fn nodes_of(angles: &[f64], lengths: Option<&[f64]>, out: &mut Vec<Point>) {
    let h = length_of(lengths, angles.len());
    out.clear();
    let mut p = Point::origin();
    out.push(p);
    for (i, &phi) in angles.iter().enumerate() {
        p += h(i) * tangent(phi);
        out.push(p);
    }
}

/// Where rods of `lengths` start along the string, s = 0 at the support, and the tip's 1 last
/// (N + 1 values); i/N for equal rods (`None`).
pub fn edges(segments: usize, lengths: Option<&[f64]>, out: &mut Vec<f64>) {
    out.clear();
    match lengths {
        None => out.extend((0..=segments).map(|i| i as f64 / segments.max(1) as f64)),
        Some(length) => {
            let mut s = 0.0;
            out.push(s);
            for &l in length {
                s += l;
                out.push(s);
            }
        }
    }
}

/// The point at arc length `s` along the string whose nodes `nodes` sit at arc lengths
/// `edges` (support … tip, both increasing), from node `from` on: the node before `s` and
/// the point, so that a walk along increasing `s` starts where the last one stopped.
fn walk_to(nodes: &[Point], edges: &[f64], from: usize, s: f64) -> (usize, Point) {
    let segments = nodes.len().saturating_sub(1);
    if segments == 0 {
        return (0, nodes.first().copied().unwrap_or_else(Point::origin));
    }
    let mut i = from.min(segments - 1);
    while i + 1 < segments && edges[i + 1] <= s {
        i += 1;
    }
    let span = edges[i + 1] - edges[i];
    let frac = if span > 0.0 {
        (s - edges[i]) / span
    } else {
        0.0
    };
    (i, nodes[i] + frac * (nodes[i + 1] - nodes[i]))
}

/// Segment centres (eqs. 14–15) of equal rods with unit tangents `tangents` (cos φ_i,
/// sin φ_i): x_i = Σ_{m<i} h cos φ_m + (h/2) cos φ_i, y likewise; the support at the origin.
pub fn centres(tangents: &[Vector2<f64>]) -> Vec<Vector2<f64>> {
    let h = 1.0 / tangents.len() as f64;
    let mut end = Vector2::zeros();
    tangents
        .iter()
        .map(|t| {
            let centre = end + 0.5 * h * t;
            end += h * t;
            centre
        })
        .collect()
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
    largest_distance_of(a, None, b, None)
}

/// As [`largest_distance`], for strings whose nodes sit at arc lengths `a_edges` and
/// `b_edges` (`None`: equal segments, [`edges`]): at arc lengths evenly spread over as many
/// points as the finer has nodes.
pub fn largest_distance_of(
    a: &[Point],
    a_edges: Option<&[f64]>,
    b: &[Point],
    b_edges: Option<&[f64]>,
) -> f64 {
    let points = a.len().max(b.len()).max(2);
    let (mut on_a, mut on_b) = (Along::new(a, a_edges), Along::new(b, b_edges));
    (0..points)
        .map(|j| {
            let s = j as f64 / (points - 1) as f64;
            (on_a.at(s) - on_b.at(s)).norm()
        })
        .fold(0.0, f64::max)
}

/// The largest distance between the nodes of string `a`, at arc lengths `a_edges`, and the
/// points of string `b` at the same arc lengths (`b`'s nodes at `b_edges`; `None`: equal
/// segments).
pub fn largest_distance_at(
    a: &[Point],
    a_edges: &[f64],
    b: &[Point],
    b_edges: Option<&[f64]>,
) -> f64 {
    let mut on_b = Along::new(b, b_edges);
    a.iter()
        .zip(a_edges)
        .map(|(p, &s)| (on_b.at(s) - p).norm())
        .fold(0.0, f64::max)
}

/// A walk along a string by increasing arc length: its nodes, where they sit (`None`: equal
/// segments, [`at_arc_length`]) and the segment the walk has reached.
pub struct Along<'a> {
    nodes: &'a [Point],
    edges: Option<&'a [f64]>,
    segment: usize,
}

impl<'a> Along<'a> {
    /// The walk along `nodes` (at arc lengths `edges`) from the support.
    pub fn new(nodes: &'a [Point], edges: Option<&'a [f64]>) -> Self {
        Self {
            nodes,
            edges,
            segment: 0,
        }
    }

    /// The point at arc length `s`, at or past the last one asked for.
    pub fn at(&mut self, s: f64) -> Point {
        let Some(edges) = self.edges else {
            return at_arc_length(self.nodes, s);
        };
        let (segment, point) = walk_to(self.nodes, edges, self.segment, s);
        self.segment = segment;
        point
    }
}

/// The tip (free end) position.
pub fn tip(angles: &[f64]) -> Point {
    tip_of(angles, None)
}

/// As [`tip`], for rods of `lengths` where they are given.
pub fn tip_of(angles: &[f64], lengths: Option<&[f64]>) -> Point {
    tip_along(
        angles.iter().map(|&phi| tangent(phi)),
        lengths,
        angles.len(),
    )
}

/// As [`tip_of`], for rods whose unit tangents are already known (a method that holds them
/// at its angles): the same sum, without a sine and cosine a rod.
pub fn tip_of_tangents(tangents: &[Vector2<f64>], lengths: Option<&[f64]>) -> Point {
    tip_along(tangents.iter().copied(), lengths, tangents.len())
}

/// Σ l_i t_i over the `segments` rods' unit tangents, support to tip (eqs. 14–15 at the last
/// node).
fn tip_along(
    tangents: impl Iterator<Item = Vector2<f64>>,
    lengths: Option<&[f64]>,
    segments: usize,
) -> Point {
    let h = length_of(lengths, segments);
    tangents
        .enumerate()
        .fold(Point::origin(), |p, (i, t)| p + h(i) * t)
}

/// Tip velocity Σ h φ̇_i n_i.
pub fn tip_velocity(angles: &[f64], angular_velocity: &[f64]) -> Vector2<f64> {
    tip_velocity_of(angles, angular_velocity, None)
}

/// As [`tip_velocity`], for rods of `lengths` where they are given.
pub fn tip_velocity_of(
    angles: &[f64],
    angular_velocity: &[f64],
    lengths: Option<&[f64]>,
) -> Vector2<f64> {
    let h = length_of(lengths, angles.len());
    angles
        .iter()
        .zip(angular_velocity)
        .enumerate()
        .fold(Vector2::zeros(), |v, (i, (&phi, &w))| {
            let (s, c) = phi.sin_cos();
            v + h(i) * w * Vector2::new(-s, c)
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

/// As [`momentum`], for rods of `lengths` (mass equal to length) where they are given: rod j
/// of length l_j, its centre at s_j = Σ_{m<j} l_m + l_j / 2.
pub fn momentum_of(
    angles: &[f64],
    angular_velocity: &[f64],
    lengths: Option<&[f64]>,
) -> Vector2<f64> {
    let Some(length) = lengths else {
        return momentum(angles, angular_velocity);
    };
    let mut start = 0.0;
    let mut p = Vector2::zeros();
    for ((&phi, &w), &l) in angles.iter().zip(angular_velocity).zip(length) {
        let (s, c) = phi.sin_cos();
        let beyond = 1.0 - (start + 0.5 * l);
        p += l * w * beyond * Vector2::new(-s, c);
        start += l;
    }
    p
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

/// The rods' centre velocities v_i = Σ_{j<i} h φ̇_j n_j + (h/2) φ̇_i n_i of equal rods with
/// unit tangents `tangents` (n_i = (−sin φ_i, cos φ_i)) turning at `angular_velocity`: what a
/// method in maximal coordinates starts from.
pub fn centre_velocities(tangents: &[Vector2<f64>], angular_velocity: &[f64]) -> Vec<Vector2<f64>> {
    let h = 1.0 / tangents.len() as f64;
    let mut end = Vector2::zeros();
    tangents
        .iter()
        .zip(angular_velocity)
        .map(|(t, &w)| {
            let turn = h * w * Vector2::new(-t.y, t.x);
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
    tip_acceleration_of(angles, angular_velocity, angular_acceleration, None)
}

/// As [`tip_acceleration`], for rods of `lengths` where they are given.
pub fn tip_acceleration_of(
    angles: &[f64],
    angular_velocity: &[f64],
    angular_acceleration: &[f64],
    lengths: Option<&[f64]>,
) -> Vector2<f64> {
    let h = length_of(lengths, angles.len());
    let mut a = Vector2::zeros();
    for (i, ((&phi, &w), &alpha)) in angles
        .iter()
        .zip(angular_velocity)
        .zip(angular_acceleration)
        .enumerate()
    {
        let (s, c) = phi.sin_cos();
        a += h(i) * (alpha * Vector2::new(-s, c) - w * w * Vector2::new(c, s));
    }
    a
}

/// What a frame reads of the rods' motion besides their nodes: the tip's velocity and
/// acceleration and the string's momentum (mass 1), in the support's frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Motion {
    pub tip_velocity: Vector2<f64>,
    pub momentum: Vector2<f64>,
    pub tip_acceleration: Vector2<f64>,
}

/// [`nodes_of`] into `nodes`, and [`tip_velocity_of`], [`momentum_of`] and
/// [`tip_acceleration_of`], in one pass over the rods: one sine and cosine a rod where the
/// four took four (a small run's frames spent 6 % of its CPU on them), and none where the
/// caller has the rods' `tangents`, (cos φ_i, sin φ_i) of `angles` (a frame takes those its
/// method carries, to round-off the angles' own: [`crate::methods::Observation::tangent`]).
pub fn motion_of(
    angles: &[f64],
    tangents: Option<&[Vector2<f64>]>,
    angular_velocity: &[f64],
    angular_acceleration: &[f64],
    lengths: Option<&[f64]>,
    nodes: &mut Vec<Point>,
) -> Motion {
    let (n, rates) = (angles.len(), (angular_velocity, angular_acceleration));
    let equal = std::iter::repeat(1.0 / n as f64);
    // Each case its own loop, so that the pass has no branch a rod: the tangents given or
    // worked out, rods of 1/N or of given lengths.
    match (tangents.filter(|t| t.len() == n), lengths) {
        (Some(t), None) => motion_along(t.iter().copied(), equal, rates, nodes),
        (Some(t), Some(l)) => motion_along(t.iter().copied(), l.iter().copied(), rates, nodes),
        (None, lengths) => {
            let t = angles.iter().map(|&phi| tangent(phi));
            motion_along(t, (0..n).map(length_of(lengths, n)), rates, nodes)
        }
    }
}

/// [`motion_of`]'s pass over rods of unit tangents `tangents` and lengths `lengths`, turning
/// at the rates and accelerations `rates`.
#[inline(always)]
fn motion_along(
    tangents: impl ExactSizeIterator<Item = Vector2<f64>>,
    lengths: impl Iterator<Item = f64>,
    (angular_velocity, angular_acceleration): (&[f64], &[f64]),
    nodes: &mut Vec<Point>,
) -> Motion {
    let n = tangents.len();
    // Every node written in place, the support's first.
    nodes.clear();
    nodes.resize(n + 1, Point::origin());
    let mut p = Point::origin();
    let (mut start, mut motion) = (0.0, Motion::default());
    let mut rod = |node: &mut Point, t: Vector2<f64>, l: f64, w: f64, alpha: f64| {
        let normal = Vector2::new(-t.y, t.x);
        p += l * t; // eqs. (14)–(15)
        *node = p;
        motion.tip_velocity += l * w * normal;
        motion.momentum += l * w * (1.0 - (start + 0.5 * l)) * normal;
        motion.tip_acceleration += l * (alpha * normal - w * w * t);
        start += l;
    };
    let rods = nodes[1..].iter_mut().zip(tangents.zip(lengths));
    if angular_velocity.len() == n && angular_acceleration.len() == n {
        let motions = angular_velocity.iter().zip(angular_acceleration);
        for ((node, (t, l)), (&w, &alpha)) in rods.zip(motions) {
            rod(node, t, l, w, alpha);
        }
    } else {
        // (A rate or acceleration not given is zero: the nodes are always all drawn.)
        let at = |values: &[f64], i: usize| values.get(i).copied().unwrap_or(0.0);
        for (i, (node, (t, l))) in rods.enumerate() {
            rod(
                node,
                t,
                l,
                at(angular_velocity, i),
                at(angular_acceleration, i),
            );
        }
    }
    motion
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_centre_lies_midway_between_its_nodes_and_moves_with_the_string_s_momentum() {
        let angles = [0.3, -0.2, 1.1, 0.7, -1.4];
        let rates = [0.5, 2.0, -1.5, 0.25, 3.0];
        let tangents: Vec<_> = angles.iter().map(|&a| tangent(a)).collect();
        let mut each = Vec::new();
        nodes(&angles, &mut each);
        for (centre, ends) in centres(&tangents).iter().zip(each.windows(2)) {
            assert!((centre - 0.5 * (ends[0].coords + ends[1].coords)).norm() < 1e-15);
        }
        let h = 1.0 / angles.len() as f64;
        let velocities = centre_velocities(&tangents, &rates);
        let momentum: Vector2<f64> = velocities.iter().map(|v| h * v).sum();
        assert!((momentum - momentum_of(&angles, &rates, None)).norm() < 1e-14);
    }

    #[test]
    fn the_motion_in_one_pass_is_the_four_figures_each_by_its_own() {
        let angles = [0.3, -0.2, 1.1, 0.7, -1.4];
        let rates = [0.5, 2.0, -1.5, 0.25, 3.0];
        let accelerations = [-1.0, 0.4, 2.5, -0.3, 0.8];
        let graded = [0.3, 0.25, 0.2, 0.15, 0.1];
        for lengths in [None, Some(&graded[..])] {
            let mut nodes = Vec::new();
            let motion = motion_of(&angles, None, &rates, &accelerations, lengths, &mut nodes);
            let mut each = Vec::new();
            nodes_of(&angles, lengths, &mut each);
            let close = |a: Vector2<f64>, b: Vector2<f64>| (a - b).norm() < 1e-14;
            assert!(
                nodes
                    .iter()
                    .zip(&each)
                    .all(|(a, b)| close(a.coords, b.coords))
            );
            assert_eq!(nodes.len(), each.len());
            assert!(close(
                motion.tip_velocity,
                tip_velocity_of(&angles, &rates, lengths)
            ));
            assert!(close(
                motion.momentum,
                momentum_of(&angles, &rates, lengths)
            ));
            let a = tip_acceleration_of(&angles, &rates, &accelerations, lengths);
            assert!(close(motion.tip_acceleration, a));
            // A method that gives no accelerations still has every node drawn.
            let bare = motion_of(&angles, None, &rates, &[], lengths, &mut nodes);
            assert_eq!(nodes.len(), each.len());
            assert!(close(bare.tip_velocity, motion.tip_velocity));
            // Given the angles' tangents, the same to the bit; given too few, they are
            // worked out.
            let tangents: Vec<_> = angles.iter().map(|&phi| tangent(phi)).collect();
            for given in [&tangents[..], &tangents[..2]] {
                let mut from_tangents = Vec::new();
                let told = motion_of(
                    &angles,
                    Some(given),
                    &rates,
                    &accelerations,
                    lengths,
                    &mut from_tangents,
                );
                assert_eq!((told, &from_tangents), (motion, &nodes));
            }
        }
    }

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
    fn rods_of_their_own_lengths_are_compared_at_equal_arc_length() {
        use std::f64::consts::FRAC_PI_2;
        // The same string bent at a right angle at s = 1/2, as 4 equal rods and as 4 rods of
        // lengths 0.1, 0.4, 0.3, 0.2.
        let equal_angles = [0.0, 0.0, FRAC_PI_2, FRAC_PI_2];
        let lengths = [0.1, 0.4, 0.3, 0.2];
        let graded_angles = [0.0, 0.0, FRAC_PI_2, FRAC_PI_2];
        let (mut a, mut b, mut edges) = (Vec::new(), Vec::new(), Vec::new());
        nodes(&equal_angles, &mut a);
        nodes_of(&graded_angles, Some(&lengths), &mut b);
        edges_of_check(&lengths, &mut edges);
        assert!(largest_distance_of(&a, None, &b, Some(&edges)) < 1e-15);
        assert!(largest_distance_at(&b, &edges, &a, None) < 1e-15);
        assert!((tip_of(&graded_angles, Some(&lengths)) - Point::new(0.5, 0.5)).norm() < 1e-15);
        // Moved apart at the tip by 0.1: the largest distance says so.
        let bent = [0.0, 0.0, FRAC_PI_2, 0.0];
        nodes_of(&bent, Some(&lengths), &mut b);
        let apart = largest_distance_of(&a, None, &b, Some(&edges));
        assert!(
            (apart - (0.2f64.powi(2) * 2.0).sqrt()).abs() < 1e-12,
            "{apart}"
        );
        // The momentum of rods of all but equal lengths is the equal rods' own.
        let (phi, omega) = ([0.3, -0.2, 1.1, 0.7], [1.0, -2.0, 0.5, 3.0]);
        let quarter = [0.25; 4];
        let (m, m_of) = (
            momentum(&phi, &omega),
            momentum_of(&phi, &omega, Some(&quarter)),
        );
        assert!((m - m_of).norm() < 1e-15, "{m:?} {m_of:?}");
    }

    /// [`edges`] of rods of `lengths`, checked to end at 1.
    fn edges_of_check(lengths: &[f64], out: &mut Vec<f64>) {
        edges(lengths.len(), Some(lengths), out);
        assert!((out[lengths.len()] - 1.0).abs() < 1e-15);
    }
}
