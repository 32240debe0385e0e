//! A study stopped by Ctrl-C or SIGTERM: it starts no more runs, writes nothing, says so and
//! ends as interrupted (exit status 130). Its files are made from every run or not at all.

mod common;

use common::cli::{ROPE, Scratch, signal_and_wait, start, stderr_of, study_args};
use rope::run::Verdict;
use rope::service::notices::Collected;
use rope::service::{Session, study};
use std::process::Child;
use std::sync::Arc;
use std::sync::atomic::Ordering;
use std::time::Duration;

/// Sends SIGINT to the study `child` 1.5 s after it started, and waits for it: it must end
/// with status 130, saying that it wrote nothing. Returns what it said.
fn interrupted_mid_study(mut child: Child) -> String {
    std::thread::sleep(Duration::from_millis(1500));
    let (status, _) = signal_and_wait(&mut child, "-INT", Duration::from_secs(120));
    let said = stderr_of(&mut child);
    assert_eq!(status.code(), Some(130), "{said}");
    assert!(said.contains("nothing was written"), "{said}");
    said
}

/// Every kind of study, stopped before its first run: none writes a file into its folder,
/// and each says that it wrote nothing.
#[test]
fn each_study_stopped_before_it_starts_writes_nothing_and_ends_interrupted() {
    let dir = Scratch::new("study-stopped");
    let kinds: [&[&str]; 5] = [
        &[
            "--segments",
            "10,20",
            "--dts",
            "1e-2",
            "--reference-segments",
            "40",
        ],
        &["--long-run", "5"],
        &["--blow-up", "5"],
        &["--estimate-check"],
        &["--tolerance-check", "quick"],
    ];
    for (i, flags) in kinds.iter().enumerate() {
        let out = dir.path(&i.to_string());
        let mut all = flags.to_vec();
        all.extend(["--out", out.to_str().unwrap()]);
        let heard = Arc::new(Collected::default());
        let session = Session::new(heard.clone(), "rope (a test)");
        session.stop.store(true, Ordering::SeqCst);
        let verdict = study::study(&study_args(&all), &session).expect("the study ends");
        assert_eq!(verdict, Verdict::Interrupted, "{flags:?}");
        let written: Vec<_> = std::fs::read_dir(&out)
            .map(|d| d.flatten().map(|e| e.file_name()).collect())
            .unwrap_or_default();
        assert!(written.is_empty(), "{flags:?} wrote {written:?}");
        let said: Vec<String> = heard.notices().into_iter().map(|n| n.text).collect();
        assert!(
            said.iter().any(|t| t.contains("nothing was written")),
            "{flags:?}: {said:?}"
        );
    }
}

/// `rope study` given SIGINT while its grid runs: it ends with status 130, without
/// `study.csv` or its findings, and says why.
#[test]
fn sigint_mid_study_ends_it_interrupted_with_nothing_written() {
    let dir = Scratch::new("study-sigint");
    let out = dir.path("out");
    // A reference at N = 200 (about 9 s of wall on 2 cores) and 16 runs of 30 time units
    // (4 s more): the signal comes while the reference runs, which stops it there.
    let child = start(&[
        "study",
        "--duration",
        "30",
        "--segments",
        "50,100",
        "--dts",
        "1e-3,5e-4",
        "--reference-segments",
        "200",
        "--out",
        out.to_str().unwrap(),
    ]);
    let said = interrupted_mid_study(child);
    assert!(!out.join("study.csv").exists(), "{said}");
    assert!(!out.join("findings.md").exists(), "{said}");
}

/// `rope study --tolerance-check quick` given SIGINT while its references run (the runs at
/// N = 400, 800 and 1 600 to t = 3, kept in a folder of kept runs): the run at N = 1 600,
/// some 18 s of CPU, stops partway, so it is not kept, and the check ends with 130.
#[test]
fn sigint_during_the_checks_references_stops_their_runs_partway() {
    let dir = Scratch::new("check-sigint");
    let (out, kept) = (dir.path("out"), dir.path("kept"));
    let child = std::process::Command::new(ROPE)
        .args(["study", "--tolerance-check", "quick", "--out"])
        .arg(&out)
        .env(rope::study::run_cache::ENV, &kept)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("the rope binary runs");
    let said = interrupted_mid_study(child);
    let finest: Vec<_> = std::fs::read_dir(&kept)
        .map(|d| d.flatten().map(|e| e.file_name()).collect())
        .unwrap_or_default();
    assert!(
        !finest
            .iter()
            .any(|name| name.to_string_lossy().contains("-1600-")),
        "the run at N = 1 600 finished: {finest:?}\n{said}"
    );
    assert!(!out.join("tolerance_check.md").exists(), "{said}");
}
