//! The study split into shards: merged, the shards give the same rows and findings as one
//! whole run (CPU columns aside); a missing, duplicated or incomplete shard is an error that
//! names what is missing; the SLURM script's command lines run the shards.

mod common;

use common::cli::Scratch;
use rope::methods::MethodKind;
use rope::model::Scene;
use rope::study::shard::{self, MergeError, ReferenceFile, Shard};
use rope::study::{self, Row, Spec};
use std::path::PathBuf;
use std::process::Command;

const FINEST: usize = 100;

fn spec() -> Spec {
    Spec {
        scene: Scene::Release { angle_deg: 30.0 },
        duration: 0.5,
        methods: MethodKind::ALL.to_vec(),
        segments: vec![10, 20, 50],
        dts: vec![1e-3, 1e-2],
    }
}

/// The study's reference of [`spec`], as a file would hold it.
fn reference_file(spec: &Spec) -> ReferenceFile {
    let r = study::reference(&spec.scene, spec.duration, FINEST, &|| ()).unwrap();
    ReferenceFile::new(spec.scene, spec.duration, FINEST, &r)
}

/// Runs the 3 shards of [`spec`] into `root/0`, `root/1`, `root/2`.
fn run_shards(root: &std::path::Path, reference: &ReferenceFile) -> Vec<PathBuf> {
    (0..3)
        .map(|index| {
            let dir = root.join(index.to_string());
            let shard = Shard { index, count: 3 };
            study::execute_shard(
                &spec(),
                shard,
                Some(reference.clone()),
                FINEST,
                &dir,
                &|| {},
            )
            .unwrap();
            dir
        })
        .collect()
}

/// What a row measured, without its CPU time.
fn measured(r: &Row) -> String {
    format!(
        "{} {} {:e} {:?} {:?} {:?} {:?}",
        r.method, r.segments, r.dt, r.status, r.energy_deviation, r.tip_error, r.shape_error
    )
}

#[test]
fn three_shards_merged_give_the_rows_and_findings_of_one_whole_run() {
    let scratch = Scratch::new("shard-merge");
    let root = &scratch.0;
    let reference = reference_file(&spec());
    let whole = study::execute_with(
        &spec(),
        reference.reference(),
        &root.join("whole"),
        "the command",
        &|| {},
    )
    .unwrap();
    let dirs = run_shards(root, &reference);
    let merged = study::execute_merge(&dirs, &root.join("merged"), "the command").unwrap();
    let rows = |rows: &[Row]| rows.iter().map(measured).collect::<Vec<_>>();
    assert_eq!(rows(&merged.rows), rows(&whole.rows));
    assert_eq!(merged.rows.len(), MethodKind::ALL.len() * 3 * 2);
    // The findings, with the whole run's CPU times in the merged rows (the rest is measured).
    let mut with_whole_cpu = merged.rows.clone();
    for (m, w) in with_whole_cpu.iter_mut().zip(&whole.rows) {
        m.cpu_seconds = w.cpu_seconds;
        m.ns_per_segment_step = w.ns_per_segment_step;
    }
    let findings = study::findings::Findings::from_rows(&with_whole_cpu);
    assert_eq!(
        findings.markdown(&merged.reference, "the command"),
        whole.markdown
    );
    for chart in ["work_precision.png", "stability_map.png"] {
        assert!(root.join("merged").join(chart).exists(), "{chart}");
    }
}

#[test]
fn a_missing_duplicated_or_incomplete_shard_is_an_error_naming_what_is_missing() {
    let scratch = Scratch::new("shard-errors");
    let root = &scratch.0;
    let reference = reference_file(&spec());
    let dirs = run_shards(root, &reference);

    let err = shard::merge(&[dirs[0].clone(), dirs[2].clone()]).unwrap_err();
    assert!(matches!(err, MergeError::Missing { .. }), "{err}");
    let text = err.to_string();
    assert!(text.contains("shard 1 of 3 missing"), "{text}");
    for (method, n, dt) in (Shard { index: 1, count: 3 }).cells(&spec()) {
        let cell = format!("{method} N = {n} k = {dt:e}");
        assert!(text.contains(&cell), "{cell} not named in: {text}");
    }

    let twice = [
        dirs[0].clone(),
        dirs[1].clone(),
        dirs[1].clone(),
        dirs[2].clone(),
    ];
    let err = shard::merge(&twice).unwrap_err();
    assert!(matches!(err, MergeError::Duplicate { .. }), "{err}");
    assert!(
        err.to_string().contains("shard 1/3 is given twice"),
        "{err}"
    );

    // A shard cut short (its last row lost) names the cell that has no row.
    let csv = dirs[2].join("study.csv");
    let text = std::fs::read_to_string(&csv).unwrap();
    let kept: Vec<&str> = text.lines().collect();
    let lost = kept.last().unwrap().to_owned();
    std::fs::write(&csv, kept[..kept.len() - 1].join("\n") + "\n").unwrap();
    let err = shard::merge(&dirs).unwrap_err();
    assert!(matches!(err, MergeError::Incomplete { .. }), "{err}");
    let mut fields = lost.split(',');
    let (method, n) = (fields.next().unwrap(), fields.next().unwrap());
    assert!(
        err.to_string()
            .contains(&format!("missing {method} N = {n} k = ")),
        "{err}"
    );
}

#[test]
fn the_slurm_script_parses_and_its_array_tasks_run_the_shards() {
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/scripts/study-slurm.sh");
    let syntax = Command::new("bash").args(["-n", script]).output().unwrap();
    assert!(syntax.status.success(), "{syntax:?}");
    let text = std::fs::read_to_string(script).unwrap();
    assert!(text.contains("#SBATCH --array=0-7"));
    let scratch = Scratch::new("shard-slurm");
    let root = &scratch.0;
    let flags = [
        "--segments",
        "10,20",
        "--dts",
        "1e-2",
        "--duration",
        "0.5",
        "--reference-segments",
        "40",
    ];
    let rope = env!("CARGO_BIN_EXE_rope");
    let reference = root.join("shards/reference");
    let made = Command::new(rope)
        .arg("study")
        .args(flags)
        .args(["--reference-only", "--out", reference.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(made.status.success(), "{made:?}");
    for task in 0..8 {
        let run = |dry: bool| {
            let mut c = Command::new("bash");
            c.arg(script)
                .args(flags)
                .env("SLURM_ARRAY_TASK_ID", task.to_string())
                .env("OUT", root)
                .env("ROPE", rope);
            if dry {
                c.env("DRY_RUN", "1");
            }
            c.output().unwrap()
        };
        let dry = run(true);
        let line = String::from_utf8_lossy(&dry.stdout);
        assert!(
            line.contains(&format!("--shard {task}/8")) && line.contains("reference.json"),
            "{line}"
        );
        let real = run(false);
        assert!(real.status.success(), "task {task}: {real:?}");
    }
    let dirs: Vec<PathBuf> = (0..8).map(|i| root.join(format!("shards/{i}"))).collect();
    let (_, _, rows) = shard::merge(&dirs).unwrap();
    assert_eq!(rows.len(), MethodKind::STUDIED.len() * 2);
}

#[test]
fn a_shard_out_of_range_or_a_reference_of_another_study_is_refused_naming_the_flag() {
    let rope = env!("CARGO_BIN_EXE_rope");
    let out = Command::new(rope)
        .args(["study", "--shard", "8/8", "--out", "/tmp"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("--shard") && stderr.contains("0 ≤ I < N"),
        "{stderr}"
    );

    let scratch = Scratch::new("shard-other-reference");
    let root = &scratch.0;
    let made = Command::new(rope)
        .args(["study", "--duration", "0.5", "--segments", "10,20"])
        .args(["--reference-only", "--out", root.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(made.status.success(), "{made:?}");
    let file = root.join(shard::REFERENCE);
    let other = Command::new(rope)
        .args([
            "study",
            "--duration",
            "1",
            "--segments",
            "10,20",
            "--shard",
            "0/2",
        ])
        .args([
            "--reference",
            file.to_str().unwrap(),
            "--out",
            root.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert_eq!(other.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&other.stderr);
    assert!(
        stderr.contains("reference =")
            && stderr.contains("to t = 0.5")
            && stderr.contains("to t = 1"),
        "{stderr}"
    );
}
