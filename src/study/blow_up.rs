//! `rope study --blow-up T`: how long the report's scheme lasts before it blows up, and what
//! grows first. Its time to divergence over N × k (up to T time units), and the grid-scale
//! sawtooth along the free end at a few instants before the blow-up, N = 100.

use super::progress::{Progress, Stopped};
use crate::methods::{MethodKind, Observation, REPORT};
use crate::model::Scene;
use crate::run::simulate;
use rayon::prelude::*;

/// Segment counts of the map.
pub const SEGMENTS: [usize; 5] = [25, 50, 100, 200, 400];
/// Time steps of the map, as fractions of the method's estimated stability limit.
pub const FRACTIONS: [f64; 6] = [0.05, 0.1, 0.2, 0.35, 0.5, 0.7];
/// The sawtooth is shown this long before the blow-up.
pub const BEFORE: [f64; 5] = [20.0, 5.0, 2.0, 1.0, 0.3];

/// How long one run lasted.
#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct Lifetime {
    pub segments: usize,
    pub dt: f64,
    /// When it diverged; `None` if it lasted the whole duration.
    pub diverged_at: Option<f64>,
}

/// The (N, k) of every run of the map: [`SEGMENTS`] × [`FRACTIONS`] of the limit.
pub fn cells() -> Vec<(usize, f64)> {
    let method = REPORT.method;
    SEGMENTS
        .iter()
        .flat_map(|&n| {
            FRACTIONS
                .iter()
                .map(move |&f| (n, f * method.stability_limit(n)))
        })
        .collect()
}

/// The report's method from `scene` over [`SEGMENTS`] × [`FRACTIONS`], each run to
/// `duration` or its divergence, in parallel. `progress` counts each run, and may stop them
/// before the next ([`Stopped`]).
pub fn lifetimes(
    scene: &Scene,
    duration: f64,
    progress: &impl Progress,
) -> Result<Vec<Lifetime>, Stopped> {
    let method = REPORT.method;
    cells()
        .par_iter()
        .map(|&(segments, dt)| {
            progress.check()?;
            let diverged_at = method.build(scene, segments, dt).ok().and_then(|mut m| {
                simulate::run_to(m.as_mut(), duration)
                    .diverged
                    .map(|d| d.time)
            });
            progress.done();
            Ok(Lifetime {
                segments,
                dt,
                diverged_at,
            })
        })
        .collect()
}

/// The shape of the string just before it blows up.
#[derive(Clone, Debug)]
pub struct Sawtooth {
    pub method: MethodKind,
    pub segments: usize,
    pub dt: f64,
    pub diverged_at: f64,
    /// At each instant t: (s, φ_i − (φ_{i−1} + 2φ_i + φ_{i+1})/4) along the interior segments
    /// (a smooth profile leaves O(h²) there; a sawtooth (−1)^i a keeps all of a).
    pub profiles: Vec<(f64, Vec<(f64, f64)>)>,
    /// The largest |φ̇| of the last segment at each instant, and of any segment.
    pub last_rate: Vec<(f64, f64, f64)>,
}

/// The report's method at N = 100 and `dt` from `scene`, run to its blow-up (within
/// `duration`), then again to [`BEFORE`] instants before it. `None` if it does not blow up.
pub fn sawtooth(scene: &Scene, dt: f64, duration: f64) -> anyhow::Result<Option<Sawtooth>> {
    let (method, segments) = (REPORT.method, REPORT.segments);
    let mut first = method.build(scene, segments, dt)?;
    let Some(diverged) = simulate::run_to(first.as_mut(), duration).diverged else {
        return Ok(None);
    };
    let mut again = method.build(scene, segments, dt)?;
    let mut obs = Observation::default();
    let mut profiles = Vec::new();
    let mut last_rate = Vec::new();
    for before in BEFORE {
        let t = diverged.time - before;
        if t <= 0.0 {
            continue;
        }
        while again.time() < t - 0.5 * dt {
            again.step()?;
        }
        again.observe(&mut obs);
        let phi = &obs.angle;
        let h = 1.0 / segments as f64;
        let profile = (1..segments - 1)
            .map(|i| {
                let smooth = (phi[i - 1] + 2.0 * phi[i] + phi[i + 1]) / 4.0;
                ((i as f64 + 0.5) * h, phi[i] - smooth)
            })
            .collect();
        profiles.push((again.time(), profile));
        let rates = &obs.angular_velocity;
        let fastest = rates.iter().fold(0.0, |m: f64, w| m.max(w.abs()));
        last_rate.push((again.time(), rates[segments - 1].abs(), fastest));
    }
    Ok(Some(Sawtooth {
        method,
        segments,
        dt,
        diverged_at: diverged.time,
        profiles,
        last_rate,
    }))
}

/// The map and the sawtooth as Markdown.
pub fn markdown(
    scene: &Scene,
    lifetimes: &[Lifetime],
    saw: Option<&Sawtooth>,
    duration: f64,
    command: &str,
) -> String {
    let method = REPORT.method;
    let mut text = format!(
        "# When the report's scheme blows up\n\n`{command}`\n\n\
         Time to divergence of the {method} method from the {scene}, each run to t = {duration} \
         at most (\"lasted\" if it got there). k is a fraction of the estimated stability limit.\n\n\
         | N | {} |\n|---|{}\n",
        FRACTIONS.map(|f| format!("{f} × limit")).join(" | "),
        "---|".repeat(FRACTIONS.len())
    );
    for n in SEGMENTS {
        let cells: Vec<String> = lifetimes
            .iter()
            .filter(|l| l.segments == n)
            .map(|l| match l.diverged_at {
                Some(t) => format!("{t:.1} (k = {:.1e})", l.dt),
                None => format!("lasted (k = {:.1e})", l.dt),
            })
            .collect();
        text += &format!("| {n} | {} |\n", cells.join(" | "));
    }
    if let Some(s) = saw {
        text += &format!(
            "\n## Before the blow-up: {}, N = {}, k = {:e}, diverged at t = {:.2}\n\n\
             | t | largest sawtooth \\|φ_i − (φ_{{i−1}} + 2φ_i + φ_{{i+1}})/4\\| | where (s) | \\|φ̇\\| of the last segment | largest \\|φ̇\\| |\n|---|---|---|---|---|\n",
            s.method, s.segments, s.dt, s.diverged_at
        );
        for ((t, profile), (_, last, fastest)) in s.profiles.iter().zip(&s.last_rate) {
            let (at, worst) =
                profile.iter().fold(
                    (0.0, 0.0),
                    |(a, w), &(s, r)| if r.abs() > w { (s, r.abs()) } else { (a, w) },
                );
            text += &format!("| {t:.2} | {worst:.2e} | {at:.3} | {last:.2} | {fastest:.2} |\n");
        }
    }
    text
}
