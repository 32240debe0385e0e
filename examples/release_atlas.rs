//! The release atlas: the worst tip error to t = 3 of the rods (the chain at its tolerance
//! step) from each release angle 0°, 10°, …, 90° at N = 16 … 566, against a reference; and
//! the same at the held-out angles 5°, 15°, …, 85°, which measure how far an angle between two
//! of the atlas's can stray from them. A reference is read (`--references`, below) or computed
//! as the tolerance check's are: the graded rods from 20° up, else the chain
//! (`tolerance_check::reference_method`), extrapolated from N = 800, 1600 and 3200.
//! `scripts/release-atlas.sh` runs it, reading the check's committed references, and writes
//! `assets/release-atlas/atlas.csv`, which `--tolerance` reads at build time
//! (`rope::plan::atlas`).
//!
//! `release_atlas graded`: the same of the graded rods (`--method graded`) at their tolerance
//! step, from 20° up ([`GRADED_FROM`]); `scripts/release-atlas.sh graded` writes
//! `assets/release-atlas/graded-atlas.csv`. `release_atlas graded 30,40`: those angles' rows
//! alone, measured in that order (each angle's rows are printed as soon as they are done).
//!
//! `release_atlas graded --until 5`: the graded rods' worst tip error to t = 5, from 40° up
//! ([`LONGER_FROM`]), against references refined towards [`LONGER_REFINED_TO`], once at most;
//! `scripts/release-atlas.sh graded --until 5` writes `assets/release-atlas/graded-atlas-t5.csv`.
//!
//! Each row runs to N = 1131, the chain's from 20° up to 566 ([`CHAIN_MEASURED_TO`]) and below
//! 20° to 3200 where its reference could judge 1e-4 ([`reach`]); `--to N` sets another end
//! (one of [`SEGMENTS`]).
//!
//! `release_atlas graded --add 1600`: each angle's entry at that one N (one of [`SEGMENTS`])
//! alone, to be added to its committed row, against a reference refined from N = 1600 until
//! it could judge 1e-4 ([`ADDED_REFINED_TO`]; runs up to N = 12 800);
//! `scripts/release-atlas.sh graded --add 1600` merges the entries into `graded-atlas.csv`.
//!
//! `release_atlas … --references PATH`: where PATH (a references CSV as `rope study
//! --tolerance-check` writes, or a folder of them; the flag may be repeated) holds an angle's
//! reference whose own error at the frames is at most [`ADDED_REFINED_TO`] (it can judge
//! 1e-4, the tightest tolerance an atlas serves) or what the atlas would refine its own
//! towards, the least such is read and measured against instead of computed (at its rows:
//! every frame is one). The rows then name it `read` in their `reference_segments`
//! column (`plan::atlas` does not read that column).
//!
//! A reference whose own error is above [`REFINED_TO`] is made from N = 1600, 3200 and 6400
//! instead (`--refine-once`: never further). `--read-any` reads the least-erring reference the
//! files hold whatever its own error (the atlas trusts only the entries it can judge): at every
//! 1/3000 the committed references from 70° and 80° (N = 6400) err by 2.1e-5 and 1.5e-5 (from
//! 50° and 60° by 1.6e-5 and 1.4e-5 until those from runs to N = 25 600 replaced them), where
//! one computed here (N = 3200) errs by 3.5e-5. The graded rods' is doubled once more (to at most [`TWICE_REFINED`]) where it
//! keeps the atlas from trusting an entry it needs: at an atlas angle, any entry (the choices
//! read the row up to N = 1131); at a held-out angle, an entry whose neighbours the committed
//! atlas trusts and which, at its bound, would stray above them (it could set the margin).

use rayon::prelude::*;
use rope::methods::MethodKind;
use rope::model::Scene;
use rope::plan::atlas::{
    ATLAS_ANGLES, Atlas, GRADED_FROM, HELD_OUT_ANGLES, LONGER_FROM, REFERENCE_MARGIN, SEGMENTS,
    WINDOW, trusted,
};
use rope::study::read_reference::{CheckReference, read_all};
use rope::study::tip_reference::TipReference;
use rope::study::tolerance_check::{best_read, measure, reference_method};
use std::io::Write;
use std::path::PathBuf;

/// The reference's N: runs at N/2, N and 2N.
const REFERENCE_SEGMENTS: usize = 1600;

/// The own error a reference is refined towards, by one doubling of its N (one more run, at
/// 4N): the atlas trusts errors down to ten times its reference's own, and the graded rods
/// near N = 800 err by 4e-5 to 7e-5 (1e-4 with the atlas's margins). Where one doubling
/// does not reach it, the refined reference still lets the atlas trust smaller errors.
const REFINED_TO: f64 = 3e-6;

/// The largest N a reference is refined to (its finest run at 2N): one doubling.
const REFINED_SEGMENTS: usize = 2 * REFERENCE_SEGMENTS;

/// The largest N a reference is doubled to: its finest run at 12 800, about 1 300 s of CPU
/// (`docs/measurements.md`).
const TWICE_REFINED: usize = 2 * REFINED_SEGMENTS;

/// The own error a reference of a longer window ([`WINDOW`] < `--until`) is refined towards.
const LONGER_REFINED_TO: f64 = 1e-5;

/// The largest N measured unless `--to` or [`reach`] says otherwise.
const MEASURED_TO: usize = 1131;

/// The largest N the chain's rows are measured to from [`GRADED_FROM`] up. Measured on to
/// 1131 against the committed references (`assets/release-atlas/chain-to-1131.csv`), its
/// held-out angles stray up to 1.96 times above their neighbours (65° at N = 1131; 1.36 at
/// 800), where up to N = 566 they stray at most 1.22 times: the one margin of the atlas would
/// be 1.96 at every N, and the choices at 1e-2 and 1e-3 between the angles would pay it. From
/// 20° up the graded rods are the cheaper where the chain would need more than 566.
const CHAIN_MEASURED_TO: usize = 566;

/// The largest N the chain's rows are measured to below [`GRADED_FROM`], where no other rods
/// may be chosen: from 10° the chain needs about 2000 rods for 1e-4.
const CHAIN_ALONE_TO: usize = 3200;

/// The tolerance the chain's rows below [`GRADED_FROM`] are measured on for.
const CHAIN_ALONE_FOR: f64 = 1e-4;

/// The own error the reference of an added entry (`--add N`) is refined towards: a tenth of
/// 1e-4, so that the entry may serve 1e-4 (the tolerance check's rule), its bound its error
/// plus at most this.
const ADDED_REFINED_TO: f64 = REFERENCE_MARGIN * CHAIN_ALONE_FOR;

/// A reference's own error below this is round-off (the vertical release hangs still): no
/// doubling can make the atlas trust errors of that size.
const ROUND_OFF: f64 = 1e-12;

fn main() -> anyhow::Result<()> {
    let mut method = MethodKind::Chain;
    let mut window = WINDOW;
    let mut to = None;
    // Only this N, to add to the committed rows (`--add N`).
    let mut add = None;
    // Only these angles, where given (to remeasure some rows).
    let mut only: Option<Vec<f64>> = None;
    // References files or folders to read where they are fine enough (`--references PATH`).
    let mut references: Vec<PathBuf> = Vec::new();
    // No second doubling of a computed reference (`--refine-once`): runs up to N = 6400.
    let mut once = false;
    // Read the least-erring reference the files hold, whatever its own error (`--read-any`).
    let mut any = false;
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "graded" => method = MethodKind::Graded,
            "--refine-once" => once = true,
            "--read-any" => any = true,
            "--until" => {
                let value = args.next().unwrap_or_default();
                window = value
                    .parse()
                    .ok()
                    .filter(|w: &f64| w.is_finite() && *w > 0.0)
                    .ok_or_else(|| {
                        anyhow::anyhow!("--until takes a duration > 0 ({value:?} given)")
                    })?;
            }
            "--references" => match args.next() {
                Some(path) => references.push(path.into()),
                None => anyhow::bail!("--references takes a references CSV or a folder of them"),
            },
            flag @ ("--to" | "--add") => {
                let value = args.next().unwrap_or_default();
                let n = value
                    .parse()
                    .ok()
                    .filter(|n| SEGMENTS.contains(n))
                    .ok_or_else(|| {
                        anyhow::anyhow!("{flag} takes one of {SEGMENTS:?} ({value:?} given)")
                    })?;
                match flag {
                    "--to" => to = Some(n),
                    _ => add = Some(n),
                }
            }
            list if only.is_none() && list.starts_with(|c: char| c.is_ascii_digit()) => {
                only = Some(list.split(',').map(str::parse).collect::<Result<_, _>>()?);
            }
            other => anyhow::bail!(
                "usage: release_atlas [graded] [--until T] [--to N | --add N] [--refine-once] [--read-any] [--references PATH]… [ANGLES] ({other:?} given)"
            ),
        }
    }
    let from = match method {
        MethodKind::Graded if window > WINDOW => LONGER_FROM,
        MethodKind::Graded => GRADED_FROM,
        _ => 0.0,
    };
    // Past t = 3 the atlas serves tolerances of 1e-3 and so (its entries near 1e-4 need a
    // reference within 1e-5), refined once at most: the further doubling weighs what the
    // atlas to t = 3 needs, so it is for that atlas alone.
    let longer = window > WINDOW;
    let (refined_to, most) = match (longer, add) {
        (true, _) => (LONGER_REFINED_TO, REFINED_SEGMENTS),
        (false, Some(_)) => (ADDED_REFINED_TO, TWICE_REFINED),
        (false, None) => (REFINED_TO, REFINED_SEGMENTS),
    };
    let set = |a: f64| match HELD_OUT_ANGLES.contains(&a) {
        true => "held-out",
        false => "atlas",
    };
    // The angles given, in their order (the first measured first), else every angle from
    // `from` up.
    let every: Vec<f64> = ATLAS_ANGLES
        .iter()
        .chain(&HELD_OUT_ANGLES)
        .copied()
        .filter(|&a| a >= from)
        .collect();
    let angles: Vec<f64> = only.unwrap_or_else(|| every.clone());
    if let Some(a) = angles.iter().find(|a| !every.contains(a)) {
        anyhow::bail!("{a}° is not an atlas or held-out angle from {from}° up");
    }
    let scenes: Vec<Scene> = angles
        .iter()
        .map(|&angle_deg| Scene::Release { angle_deg })
        .collect();
    let read = read_all(&references, &scenes, window)?;
    // A reference is read where it can judge the tightest tolerance an atlas serves, or is as
    // fine as the atlas would refine its own; else computed.
    let read_within = refined_to.max(ADDED_REFINED_TO);
    let angles: Vec<(&str, f64)> = angles.into_iter().map(|a| (set(a), a)).collect();
    // Each angle's rows are printed as soon as they are measured, so that a run stopped
    // early keeps the angles it finished.
    println!("set,angle_deg,segments,worst,reference_segments,reference_own_error");
    let stdout = std::sync::Mutex::new(std::io::stdout());
    angles
        .into_iter()
        .par_bridge()
        .try_for_each(|(set, angle_deg)| -> anyhow::Result<()> {
            let scene = Scene::Release { angle_deg };
            let mut reference = match best_read(&read, &scene) {
                Some(r) if any || r.own_error <= read_within => CheckReference::Read(r.clone()),
                other => {
                    if let Some(r) = other {
                        eprintln!(
                            "{set} {angle_deg}°: `{}` errs by {:.1e} at every 1/3000, above {read_within:.0e}; computed",
                            r.source.display(),
                            r.own_error
                        );
                    }
                    CheckReference::Computed(TipReference::refined_by(
                        reference_method(&scene, window),
                        &scene,
                        REFERENCE_SEGMENTS,
                        most,
                        refined_to,
                        window,
                        &|| (),
                    )?)
                }
            };
            let row = |reference: &CheckReference| -> Vec<(usize, f64)> {
                let to = to.unwrap_or_else(|| reach(method, angle_deg, reference.own_error()));
                SEGMENTS
                    .iter()
                    .filter(|&&n| add.map_or(n <= to, |added| n == added))
                    .map(|&n| {
                        let dt = method.tolerance_dt(n);
                        let worst = measure(method, &scene, n, dt, window, None, reference)
                            .map_or(f64::NAN, |m| m.worst);
                        (n, worst)
                    })
                    .collect()
            };
            let mut worst = row(&reference);
            if let CheckReference::Computed(computed) = &reference
                && method == MethodKind::Graded
                && !longer
                && !once
                && add.is_none()
                && computed.segments * 2 <= TWICE_REFINED
                && computed.own_error > ROUND_OFF
                && keeps_out(set, angle_deg, &worst, computed.own_error)
            {
                eprintln!(
                    "{set} {angle_deg}°: own error {:.1e} at N = {}; doubled",
                    computed.own_error, computed.segments
                );
                reference = CheckReference::Computed(computed.clone().doubled(&|| ())?);
                worst = row(&reference);
            }
            let own = reference.own_error();
            let segments = match &reference {
                CheckReference::Read(r) => {
                    eprintln!(
                        "{set} {angle_deg}°: reference read from `{}`, own error {own:.1e}",
                        r.source.display()
                    );
                    "read".to_owned()
                }
                CheckReference::Computed(r) => {
                    eprintln!(
                        "{set} {angle_deg}°: reference N = {} (order {:.2}), own error {own:.1e}",
                        r.segments, r.order
                    );
                    r.segments.to_string()
                }
            };
            let lines: Vec<String> = worst
                .into_iter()
                .map(|(n, worst)| format!("{set},{angle_deg},{n},{worst:.4e},{segments},{own:.2e}"))
                .collect();
            let mut out = stdout
                .lock()
                .map_err(|_| anyhow::anyhow!("stdout poisoned"))?;
            writeln!(out, "{}", lines.join("\n"))?;
            out.flush()?;
            Ok(())
        })?;
    Ok(())
}

/// The largest N measured from `angle_deg` against a reference whose own error is `own`: the
/// chain's below [`GRADED_FROM`] on to [`CHAIN_ALONE_TO`] where the reference could judge
/// [`CHAIN_ALONE_FOR`] (a tenth of it); the chain's from [`GRADED_FROM`] up to
/// [`CHAIN_MEASURED_TO`]; else (the graded rods', the chain's below 20° against a coarser
/// reference) to [`MEASURED_TO`].
fn reach(method: MethodKind, angle_deg: f64, own: f64) -> usize {
    let chain = method == MethodKind::Chain;
    match (chain, angle_deg < GRADED_FROM) {
        (true, true) if own <= REFERENCE_MARGIN * CHAIN_ALONE_FOR => CHAIN_ALONE_TO,
        (true, false) => CHAIN_MEASURED_TO,
        _ => MEASURED_TO,
    }
}

/// Whether a graded row measured against a reference of own error `own` leaves out an entry
/// the atlas needs: at an atlas angle, any it does not trust; at a held-out angle, one it does
/// not trust where the committed atlas trusts both neighbours and the entry's bound (its error
/// plus `own`) is above theirs.
fn keeps_out(set: &str, angle_deg: f64, worst: &[(usize, f64)], own: f64) -> bool {
    if set == "atlas" {
        return worst.iter().any(|&(_, e)| !trusted(e, own));
    }
    let Some(neighbours) = Atlas::committed_graded().and_then(|a| a.neighbours(angle_deg)) else {
        return false;
    };
    worst
        .iter()
        .zip(neighbours)
        .any(|(&(_, e), n)| !trusted(e, own) && n.is_some_and(|n| e + own > n))
}
