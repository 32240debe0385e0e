//! `rope run` left running: a served endpoint that late viewers join, endless and looping
//! runs, and viewers that go away mid-stream. Every process here is real: the viewer-side
//! endpoint is a second `rope` hosting Rerun's gRPC server (`--serve-grpc`), killed with
//! SIGKILL, and the late viewer reads with Rerun's own gRPC client.

mod common;

use common::cli::{
    Recording, Scratch, free_pair, rope, signal, signal_and_wait, start, stderr_lines_until,
    stderr_of, summary, wait_for,
};
use rerun::external::re_grpc_client;
use rope::recording::live::HistoryRates;
use std::process::Child;
use std::time::{Duration, Instant};

fn url(port: u16) -> String {
    format!("rerun+http://127.0.0.1:{port}/proxy")
}

/// Waits until something listens on `port`.
fn wait_listening(port: u16) {
    let started = Instant::now();
    while std::net::TcpStream::connect(("127.0.0.1", port)).is_err() {
        assert!(
            started.elapsed() < Duration::from_secs(20),
            "nothing listens on {port}"
        );
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// A viewer's side of the stream: Rerun's gRPC reader, connected to a served endpoint.
struct LateViewer {
    messages: re_log_channel::LogReceiver,
    _runtime: tokio::runtime::Runtime,
}

impl LateViewer {
    fn join(port: u16) -> Self {
        let runtime = tokio::runtime::Builder::new_multi_thread()
            .worker_threads(1)
            .enable_all()
            .build()
            .expect("a tokio runtime");
        let handle = re_async::AsyncRuntimeHandle::new_native(runtime.handle().clone());
        let uri = url(port).parse().expect("a proxy URI");
        Self {
            messages: re_grpc_client::read::stream(&handle, uri),
            _runtime: runtime,
        }
    }

    /// Reads into `rec` until `done(rec)` holds or `limit` passes; says whether it held.
    fn read_until(
        &self,
        rec: &mut Recording,
        limit: Duration,
        done: impl Fn(&Recording) -> bool,
    ) -> bool {
        use re_log_channel::{DataSourceMessage, SmartMessagePayload};
        let started = Instant::now();
        while started.elapsed() < limit {
            if done(rec) {
                return true;
            }
            if let Ok(msg) = self.messages.recv_timeout(Duration::from_millis(100))
                && let SmartMessagePayload::Msg(DataSourceMessage::LogMsg(msg)) = msg.payload
            {
                rec.add(msg);
            }
        }
        done(rec)
    }
}

#[test]
fn served_and_saved_a_late_viewer_gets_the_history_the_file_every_frame_and_sigterm_ends_it() {
    let dir = Scratch::new("serve-late");
    let (json, rrd) = (dir.path("s.json"), dir.path("s.rrd"));
    let port = free_pair();
    let mut server = start(&[
        "run",
        "--duration",
        "4",
        "--serve-grpc",
        &format!("127.0.0.1:{port}"),
        "--save",
        rrd.to_str().unwrap(),
        "--summary",
        json.to_str().unwrap(),
    ]);
    // The summary is written when the run has ended; the process then goes on serving.
    let started = Instant::now();
    while !json.exists() {
        assert!(started.elapsed() < Duration::from_secs(30), "no summary");
        std::thread::sleep(Duration::from_millis(50));
    }
    std::thread::sleep(Duration::from_millis(200));
    let frames = summary(&json)["frames_logged"].as_u64().unwrap() as usize;
    assert_eq!(frames, 241);

    // The history: the rope then at t = 0 and 4 (a shape every 4 time units), the plots at
    // 0.75 rows a time unit (every 80th frame at 60 a time unit), the parameters with the
    // page's budget.
    let rates = HistoryRates::DEFAULT;
    assert_eq!(rates.shape_interval(), 4.0);
    assert_eq!(rates.series_stride(60.0), 80);
    let viewer = LateViewer::join(port);
    let mut rec = Recording::default();
    let complete = viewer.read_until(&mut rec, Duration::from_secs(20), |r| {
        r.temporal_rows("then/segments") >= 2 && r.temporal_rows("energy/total") >= 4
    });
    let then = rec.sim_times("then/segments");
    assert!(complete, "the late viewer got the rope then at {then:?}");
    assert_eq!(then.len(), 2, "{then:?}");
    for (t, expected) in then.iter().zip([0.0, 4.0]) {
        assert!((t - expected).abs() < 1e-9, "{then:?}");
    }
    assert_eq!(
        rec.temporal_rows("rope/segments"),
        0,
        "no frame of every frame"
    );
    let energy = rec.sim_times("energy/total");
    assert_eq!(
        energy.len(),
        4,
        "0.75 rows a time unit over [0, 4]: {energy:?}"
    );
    assert!(rec.has("parameters"));

    assert!(
        wait_for(&mut server, Duration::ZERO).is_none(),
        "still serving"
    );
    let (status, took) = signal_and_wait(&mut server, "-TERM", Duration::from_secs(5));
    assert!(took < Duration::from_secs(1), "{took:?}");
    let stderr = stderr_of(&mut server);
    assert_eq!(status.code(), Some(0), "{stderr}");
    assert!(
        stderr.contains(&format!("serving at {}", url(port)))
            && stderr.contains(&url(port + 1))
            && stderr.contains("a browser page can stay open about"),
        "{stderr}"
    );
    // Served and saved at once: the file keeps every frame.
    let saved = Recording::read(&rrd);
    assert_eq!(saved.temporal_rows("rope/segments"), frames);
    assert!(!saved.has("then/segments"));
}

#[test]
fn an_endless_served_run_gives_a_late_viewer_its_history_and_a_live_picture() {
    let port = free_pair();
    let mut server = start(&[
        "run",
        "--duration",
        "inf",
        "--realtime",
        "4",
        "--serve-grpc",
        &port.to_string(),
    ]);
    wait_listening(port);
    std::thread::sleep(Duration::from_millis(1500));
    // By now the run is at t ≈ 6; the history's viewer gets the rope then from t = 0, a
    // shape every 4 time units, none missing; the live one gets pictures that replace
    // themselves.
    let every = HistoryRates::DEFAULT.shape_interval();
    let history = LateViewer::join(port);
    let live = LateViewer::join(port + 1);
    let mut rec = Recording::default();
    let got = history.read_until(&mut rec, Duration::from_secs(30), |r| {
        r.sim_times("then/segments")
            .last()
            .is_some_and(|&t| t > 20.0)
    });
    let times = rec.sim_times("then/segments");
    assert!(got, "the rope then at {times:?}");
    assert_eq!(times.first().copied(), Some(0.0), "history from t = 0");
    for (i, t) in times.iter().enumerate() {
        assert!(
            (t - every * i as f64).abs() < 0.02,
            "a shape every {every} time units: {times:?}"
        );
    }
    let mut now = Recording::default();
    let pictures = live.read_until(&mut now, Duration::from_secs(10), |r| {
        r.static_chunks("rope/segments") >= 10
    });
    assert!(
        pictures,
        "{} live pictures",
        now.static_chunks("rope/segments")
    );
    assert_eq!(
        now.temporal_rows("rope/segments"),
        0,
        "the live picture is static"
    );

    let (status, took) = signal_and_wait(&mut server, "-TERM", Duration::from_secs(5));
    assert!(took < Duration::from_secs(1), "{took:?}");
    let stderr = stderr_of(&mut server);
    assert_eq!(status.code(), Some(130), "{stderr}");
    assert!(
        stderr.contains("uses the midpoint method: it keeps the energy at every frame")
            && stderr.contains("method: midpoint, the default for a run left running"),
        "{stderr}"
    );
}

/// A viewer-side endpoint this test controls: a `rope` hosting Rerun's gRPC server, returned
/// with its port once it says it is serving. If a test running beside this one took the port
/// picked, the endpoint cannot listen there and another port is tried.
fn endpoint() -> (Child, u16) {
    for _ in 0..5 {
        let port = free_pair();
        let mut endpoint = start(&[
            "run",
            "--duration",
            "inf",
            "--realtime",
            "--log-rate",
            "1",
            "--serve-grpc",
            &format!("127.0.0.1:{port}"),
        ]);
        if stderr_lines_until(&mut endpoint, "rope: serving at").is_some() {
            return (endpoint, port);
        }
        endpoint.kill().ok();
        endpoint.wait().ok();
    }
    panic!("no endpoint could be started on five ports");
}

#[test]
fn a_killed_viewer_stops_a_connect_only_run_within_seconds_with_a_clear_message() {
    let dir = Scratch::new("viewer-killed");
    let json = dir.path("c.json");
    let (mut viewer, port) = endpoint();
    let mut run = start(&[
        "run",
        "--duration",
        "inf",
        "--realtime",
        "--connect",
        &url(port),
        "--summary",
        json.to_str().unwrap(),
    ]);
    std::thread::sleep(Duration::from_millis(1500));
    if let Some(status) = wait_for(&mut run, Duration::ZERO) {
        panic!(
            "the run ended ({status}) instead of streaming: {}",
            stderr_of(&mut run)
        );
    }
    signal(&viewer, "-KILL");
    let killed = Instant::now();
    wait_for(&mut viewer, Duration::from_secs(5)).expect("the viewer is gone");
    let status = wait_for(&mut run, Duration::from_secs(15)).expect("the run stopped");
    let took = killed.elapsed();
    let stderr = stderr_of(&mut run);
    assert!(took < Duration::from_secs(8), "took {took:?}: {stderr}");
    assert_eq!(status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("the recording is incomplete") && stderr.contains(&url(port)),
        "{stderr}"
    );
    let s = summary(&json);
    assert_eq!(s["status"], "interrupted");
    assert!(s["recording_error"].as_str().unwrap().contains(&url(port)));
    assert!(s["frames_logged"].as_u64().unwrap() >= 60);
}

#[test]
fn a_killed_viewer_leaves_a_watch_and_save_run_going_and_its_file_complete() {
    let dir = Scratch::new("viewer-killed-save");
    let (rrd, json) = (dir.path("w.rrd"), dir.path("w.json"));
    let (mut viewer, port) = endpoint();
    let mut run = start(&[
        "run",
        "--duration",
        "inf",
        "--realtime",
        "2",
        "--connect",
        &url(port),
        "--save",
        rrd.to_str().unwrap(),
        "--summary",
        json.to_str().unwrap(),
    ]);
    std::thread::sleep(Duration::from_millis(1500));
    signal(&viewer, "-KILL");
    wait_for(&mut viewer, Duration::from_secs(5)).expect("the viewer is gone");
    // The run goes on without the viewer.
    assert!(
        wait_for(&mut run, Duration::from_millis(2500)).is_none(),
        "the run stopped with its viewer: {}",
        stderr_of(&mut run)
    );
    let (status, took) = signal_and_wait(&mut run, "-TERM", Duration::from_secs(10));
    assert!(took < Duration::from_secs(1), "{took:?}");
    let stderr = stderr_of(&mut run);
    assert_eq!(status.code(), Some(130), "{stderr}");
    assert!(
        stderr.contains("warning") && stderr.contains("goes on"),
        "{stderr}"
    );
    let s = summary(&json);
    assert_eq!(s["status"], "interrupted");
    assert!(s["recording_error"].is_null(), "{}", s["recording_error"]);
    let frames = s["frames_logged"].as_u64().unwrap() as usize;
    let saved = Recording::read(&rrd);
    assert_eq!(saved.temporal_rows("rope/segments"), frames);
    // Frames from after the viewer died (t ≈ 3 at realtime 2) are in the file.
    assert!(*saved.sim_times("rope/segments").last().unwrap() > 6.0);
}

#[test]
fn a_frozen_viewer_counts_as_gone_once_it_takes_nothing_for_5_s() {
    let (mut viewer, port) = endpoint();
    let mut run = start(&[
        "run",
        "--duration",
        "inf",
        "--realtime",
        "4",
        "--connect",
        &url(port),
    ]);
    std::thread::sleep(Duration::from_millis(1500));
    signal(&viewer, "-STOP"); // alive, connected, and reading nothing
    let frozen = Instant::now();
    let status = wait_for(&mut run, Duration::from_secs(40));
    signal(&viewer, "-KILL");
    viewer.wait().ok();
    let status = status.expect("the run stopped");
    let stderr = stderr_of(&mut run);
    // Rerun's and this link's queues fill first, then 5 s of nothing taken. The queues hold
    // messages, which Rerun's batcher sends at its own pace whatever the data rate (the same
    // at --realtime 4 and 16): some 9 s here, more on a busy machine (14.1 to 15.4 s in all,
    // measured with every core busy, where 15 s had been the bound).
    assert!(
        frozen.elapsed() < Duration::from_secs(25),
        "took {:?}: {stderr}",
        frozen.elapsed()
    );
    assert_eq!(status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("took no data for 5 s"), "{stderr}");
}

#[test]
fn a_loop_runs_the_scenes_in_turn_one_after_another_on_the_timeline() {
    let dir = Scratch::new("loop");
    let rrd = dir.path("l.rrd");
    let out = rope(&[
        "run",
        "--loop",
        "2",
        "--angle",
        "30,60",
        "--duration",
        "0.5",
        "--save",
        rrd.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert_eq!(stderr.matches("release at 30°").count(), 2, "{stderr}");
    assert_eq!(stderr.matches("release at 60°").count(), 2, "{stderr}"); // each run once
    let rec = Recording::read(&rrd);
    // Four runs of 31 frames, each starting where the previous one ended.
    assert_eq!(rec.temporal_rows("rope/segments"), 4 * 31);
    assert_eq!(
        rec.sim_times("parameters"),
        [0.0, 0.5, 1.0, 1.5],
        "each run's parameters at its start"
    );
    let times = rec.sim_times("rope/segments");
    assert!((times.last().unwrap() - 2.0).abs() < 1e-9);
}

#[test]
fn service_flags_that_cannot_work_exit_2_naming_the_flag() {
    let taken = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let port = taken.local_addr().unwrap().port();
    let cases: [(&[&str], &str, i32); 7] = [
        (&["--duration", "inf", "--loop"], "loop", 2),
        (&["--duration", "inf", "--angle", "30,60"], "loop", 2),
        (&["--duration", "1", "--loop", "0"], "loop", 2),
        (&["--serve-grpc", "localhost:x"], "serve-grpc", 2),
        (&["--serve-grpc", "--server-memory-limit", "0"], "memory", 2),
        (&["--connect", "http://nowhere"], "connect", 2),
        // An address already taken is not a typo, but still named, with what would work.
        (
            &["--serve-grpc", &format!("127.0.0.1:{port}")],
            "serve-grpc",
            1,
        ),
    ];
    for (args, named, code) in cases {
        let mut full = vec!["run"];
        full.extend_from_slice(args);
        let out = rope(&full);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(code), "{args:?}: {stderr}");
        assert!(stderr.contains(named), "{args:?}: {stderr}");
    }
}

#[test]
fn a_default_page_lasts_a_week_three_methods_three_days_at_any_pace() {
    use clap::Parser as _;
    use rope::cli::{Cli, Command};
    use rope::recording::budget::Budget;
    let budget = |extra: &[&str]| {
        let mut args = vec!["rope", "run", "--duration", "inf", "--web"];
        args.extend_from_slice(extra);
        let Command::Run(run) = Cli::try_parse_from(&args).unwrap().command else {
            unreachable!()
        };
        let plans = run.plans().unwrap();
        Budget::measure(&plans[0].lanes(), run.output.history_rates())
    };
    let one = budget(&["--realtime"]);
    let three = budget(&["--realtime", "--method", "seed,chain,midpoint"]);
    assert!(one.days() >= 7.0, "{one:?}: {} days", one.days());
    assert!(three.days() >= 3.0, "{three:?}: {} days", three.days());
    // The history goes by simulated time: a faster pace sends the same bytes per time unit.
    let fast = budget(&["--realtime", "30"]);
    assert_eq!(fast.bytes_per_unit, one.bytes_per_unit);
    // And by frames of simulated time, whatever the step: a soak accelerated by a longer
    // step sends what the default step sends.
    let long_step = budget(&["--realtime", "200", "--dt", "1e-2"]);
    assert_eq!(long_step.bytes_per_unit, one.bytes_per_unit);
    assert!((one.days() / fast.days() - 30.0).abs() < 1e-9);
}
