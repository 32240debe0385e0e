//! Helpers for the tests that run the `rope` binary: scratch directories, the binary, and
//! recordings decoded with Rerun's own decoder.

use rerun::external::re_log_encoding::rrd::DecoderApp;
use rerun::external::re_log_types::LogMsg;
use rerun::log::Chunk;
use serde_json::Value;
use std::collections::BTreeMap;
use std::io::Read as _;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, ExitStatus, Output, Stdio};
use std::time::{Duration, Instant};

pub const ROPE: &str = env!("CARGO_BIN_EXE_rope");

/// A scratch directory removed at the end of the test.
pub struct Scratch(pub PathBuf);

impl Scratch {
    pub fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("rope-test-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        Self(dir)
    }
    pub fn path(&self, file: &str) -> PathBuf {
        self.0.join(file)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// `rope run ARGS` parsed as the binary parses it, for a service called in-process.
pub fn run_args(args: &[&str]) -> rope::cli::RunArgs {
    match parsed("run", args) {
        rope::cli::Command::Run(args) => args,
        rope::cli::Command::Study(_) => unreachable!(),
    }
}

/// `rope study ARGS` parsed as the binary parses it, for a service called in-process.
pub fn study_args(args: &[&str]) -> rope::cli::StudyArgs {
    match parsed("study", args) {
        rope::cli::Command::Study(args) => args,
        rope::cli::Command::Run(_) => unreachable!(),
    }
}

/// `rope COMMAND ARGS` parsed.
fn parsed(command: &str, args: &[&str]) -> rope::cli::Command {
    let mut full = vec!["rope", command];
    full.extend_from_slice(args);
    <rope::cli::Cli as clap::Parser>::try_parse_from(&full)
        .expect("the flags parse")
        .command
}

pub fn rope(args: &[&str]) -> Output {
    Command::new(ROPE)
        .args(args)
        .output()
        .expect("the rope binary runs")
}

/// What a recording holds, per entity path of the recording store: the chunks' rows.
#[derive(Default)]
pub struct Recording {
    pub chunks: BTreeMap<String, Vec<Chunk>>,
}

impl Recording {
    pub fn decode(bytes: &[u8]) -> Self {
        let mut rec = Recording::default();
        for msg in DecoderApp::decode_lazy(bytes) {
            rec.add(msg.expect("the recording decodes"));
        }
        rec
    }

    /// Takes in one message of a recording (file or stream); the blueprint is skipped.
    pub fn add(&mut self, msg: LogMsg) {
        if let LogMsg::ArrowMsg(store, arrow) = msg {
            if !store.is_recording() {
                return; // the blueprint
            }
            let chunk = Chunk::from_arrow_msg(&arrow).expect("a valid chunk");
            let path = chunk
                .entity_path()
                .to_string()
                .trim_start_matches('/')
                .to_owned();
            self.chunks.entry(path).or_default().push(chunk);
        }
    }

    /// The `sim_time` of every temporal row of `entity`, in seconds, sorted.
    pub fn sim_times(&self, entity: &str) -> Vec<f64> {
        let timeline = rerun::TimelineName::from_static_str("sim_time");
        let mut times: Vec<f64> = self
            .chunks
            .get(entity)
            .into_iter()
            .flatten()
            .filter_map(|c| c.timelines().get(&timeline))
            .flat_map(|column| column.times_raw().iter().map(|&ns| ns as f64 * 1e-9))
            .collect();
        times.sort_by(f64::total_cmp);
        times
    }

    pub fn read(path: &Path) -> Self {
        Self::decode(&std::fs::read(path).expect("the recording exists"))
    }

    /// Where `entity` was cleared on `sim_time` (a break in its plot), in seconds.
    pub fn cleared_at(&self, entity: &str) -> Vec<f64> {
        let timeline = rerun::TimelineName::from_static_str("sim_time");
        let clear = rerun::Clear::descriptor_is_recursive().component;
        self.chunks
            .get(entity)
            .into_iter()
            .flatten()
            .filter(|c| {
                c.iter_component::<rerun::components::ClearIsRecursive>(clear)
                    .any(|row| !row.is_empty())
            })
            .filter_map(|c| c.timelines().get(&timeline))
            .flat_map(|column| column.times_raw().iter().map(|&ns| ns as f64 * 1e-9))
            .collect()
    }

    /// Rows logged on the timelines (not static) for `entity`.
    pub fn temporal_rows(&self, entity: &str) -> usize {
        self.chunks
            .get(entity)
            .map(|cs| {
                cs.iter()
                    .filter(|c| !c.is_static())
                    .map(|c| c.num_rows())
                    .sum()
            })
            .unwrap_or(0)
    }

    /// The values of one component logged on the timelines for `entity`, in the order
    /// logged, each read by `read`.
    fn temporal_values<C: rerun::Component, T>(
        &self,
        entity: &str,
        component: rerun::ComponentIdentifier,
        read: impl Fn(&C) -> T + Copy,
    ) -> Vec<T> {
        self.chunks
            .get(entity)
            .into_iter()
            .flatten()
            .filter(|c| !c.is_static())
            .flat_map(|c| {
                c.iter_component::<C>(component)
                    .flat_map(|row| row.iter().map(read).collect::<Vec<T>>())
                    .collect::<Vec<T>>()
            })
            .collect()
    }

    /// The scalars logged on the timelines for `entity`, in the order logged.
    pub fn scalars(&self, entity: &str) -> Vec<f64> {
        let scalar = rerun::Scalars::descriptor_scalars().component;
        self.temporal_values(entity, scalar, |s: &rerun::components::Scalar| s.0.0)
    }

    /// The labels logged on the timelines for the points of `entity`.
    pub fn point_labels(&self, entity: &str) -> Vec<String> {
        let labels = rerun::Points2D::descriptor_labels().component;
        self.temporal_values(entity, labels, |t: &rerun::components::Text| t.to_string())
    }

    /// Per row of `entity`'s points (by sim time), the methods they belong to, told by their
    /// colours: side by side each method's tip is drawn in its colour (its finest chart
    /// colour), and the legend names the colours.
    pub fn point_methods_by_row(&self, entity: &str) -> Vec<(f64, Vec<String>)> {
        let timeline = rerun::TimelineName::from_static_str("sim_time");
        let colours = rerun::Points2D::descriptor_colors().component;
        let method_of = |c: &rerun::components::Color| {
            let [r, g, b, _] = c.0.to_array();
            rope::methods::MethodKind::ALL
                .into_iter()
                .find(|m| m.descriptor().colours.1 == [r, g, b])
                .map_or_else(|| format!("rgb({r}, {g}, {b})"), |m| m.name().to_owned())
        };
        let mut rows: Vec<(f64, Vec<String>)> = self
            .chunks
            .get(entity)
            .into_iter()
            .flatten()
            .filter(|c| !c.is_static())
            .flat_map(|c| {
                let times: Vec<f64> = c
                    .timelines()
                    .get(&timeline)
                    .map(|col| col.times_raw().iter().map(|&ns| ns as f64 * 1e-9).collect())
                    .unwrap_or_default();
                let names: Vec<Vec<String>> = c
                    .iter_component::<rerun::components::Color>(colours)
                    .map(|row| row.iter().map(method_of).collect())
                    .collect();
                times.into_iter().zip(names).collect::<Vec<_>>()
            })
            .collect();
        rows.sort_by(|a, b| a.0.total_cmp(&b.0));
        rows
    }

    /// The texts of the log lines on the timelines at `entity`.
    pub fn log_texts(&self, entity: &str) -> Vec<String> {
        let text = rerun::TextLog::descriptor_text().component;
        self.temporal_values(entity, text, |t: &rerun::components::Text| t.to_string())
    }

    /// How many static chunks of `entity` arrived (a live picture: each replaces the last).
    pub fn static_chunks(&self, entity: &str) -> usize {
        self.chunks
            .get(entity)
            .map_or(0, |chunks| chunks.iter().filter(|c| c.is_static()).count())
    }

    pub fn has(&self, entity: &str) -> bool {
        self.chunks.contains_key(entity)
    }
}

pub fn summary(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).expect("summary written")).expect("JSON")
}

/// Runs `rope` with `args`, saving its recording and summary in a scratch directory named
/// for `name`, and returns the summary and what it said. Exit status 0, or 4 where a
/// `--tolerance` run's live estimate passed EPS: the run ran either way, and the caller
/// judges its choice.
#[allow(dead_code)]
pub fn run_judged(name: &str, args: &[&str]) -> (Value, String) {
    let dir = Scratch::new(name);
    let (rrd, json) = (dir.path("t.rrd"), dir.path("t.json"));
    let mut args = args.to_vec();
    args.extend_from_slice(&[
        "--save",
        rrd.to_str().unwrap(),
        "--summary",
        json.to_str().unwrap(),
    ]);
    let out = rope(&args);
    let said = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(matches!(out.status.code(), Some(0 | 4)), "{said}");
    (summary(&json), said)
}

/// `(t, tip)` at every frame of a run's summary (its `tip_samples`).
#[allow(dead_code)]
pub fn tip_samples(summary: &Value) -> Vec<(f64, rope::model::Point)> {
    summary["tip_samples"]
        .as_array()
        .expect("tip_samples")
        .iter()
        .map(|v| {
            let at = |i: usize| v[i].as_f64().expect("a number");
            (at(0), rope::model::Point::new(at(1), at(2)))
        })
        .collect()
}

/// Starts `rope` with `args`, stderr captured.
pub fn start(args: &[&str]) -> Child {
    Command::new(ROPE)
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the rope binary runs")
}

/// Sends `signal` (as `kill` takes it: -TERM, -KILL, …) to `child`.
pub fn signal(child: &Child, signal: &str) {
    let sent = Command::new("kill")
        .args([signal, &child.id().to_string()])
        .status()
        .expect("kill runs");
    assert!(sent.success());
}

/// Waits up to `limit` for `child` to exit; `None` if it is still running then.
pub fn wait_for(child: &mut Child, limit: Duration) -> Option<ExitStatus> {
    let started = Instant::now();
    loop {
        if let Some(status) = child.try_wait().expect("try_wait") {
            return Some(status);
        }
        if started.elapsed() > limit {
            return None;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// What `child` wrote to its (piped) stderr.
pub fn stderr_of(child: &mut Child) -> String {
    let mut text = String::new();
    if let Some(mut err) = child.stderr.take() {
        err.read_to_string(&mut text).ok();
    }
    text
}

/// Sends `signal` to `child` and waits for it to exit: its status, and how long that took.
/// Fails the test if it is still running `limit` after.
pub fn signal_and_wait(child: &mut Child, sig: &str, limit: Duration) -> (ExitStatus, Duration) {
    let sent = Instant::now();
    signal(child, sig);
    let status =
        wait_for(child, limit).unwrap_or_else(|| panic!("still running {limit:?} after {sig}"));
    (status, sent.elapsed())
}

/// A port on 127.0.0.1 that nothing listens on (just now), and that no other test of this
/// process has been given. A port for `--serve-grpc` takes [`free_pair`]: `rope` serves its
/// live picture on the next one.
pub fn free_port() -> u16 {
    free_ports(1)
}

/// A free port whose next port is free too: a served run's history endpoint and its live
/// picture's.
pub fn free_pair() -> u16 {
    free_ports(2)
}

/// The first of `count` consecutive ports on 127.0.0.1 that nothing listens on and that this
/// process has not handed out before. They lie below the kernel's ephemeral range, so that
/// between the test picking them and `rope` binding them, neither another test's bind to
/// port 0 nor any outgoing connection (the late viewers', the runs' `--connect`) can take
/// one: the kernel hands those out from the ephemeral range alone.
fn free_ports(count: u16) -> u16 {
    static HANDED_OUT: std::sync::Mutex<Vec<u16>> = std::sync::Mutex::new(Vec::new());
    let mut handed_out = HANDED_OUT.lock().unwrap_or_else(|e| e.into_inner());
    let ephemeral_from = std::fs::read_to_string("/proc/sys/net/ipv4/ip_local_port_range")
        .ok()
        .and_then(|range| range.split_whitespace().next()?.parse::<u16>().ok())
        .unwrap_or(32_768);
    let (low, high) = (10_000u16, ephemeral_from.clamp(11_000, 32_768) - count);
    // Start where another suite running at the same time is unlikely to (from the process
    // id), and each search 64 ports past the last.
    let span = u32::from(high - low);
    let start = std::process::id().wrapping_mul(2_654_435_761) + 64 * handed_out.len() as u32;
    let mut port = low + (start % span) as u16;
    for _ in 0..span {
        let ports = port..port + count;
        let free = ports.clone().all(|p| {
            !handed_out.contains(&p) && std::net::TcpListener::bind(("127.0.0.1", p)).is_ok()
        });
        if free {
            handed_out.extend(ports);
            return port;
        }
        port = if port + 1 >= high { low } else { port + 1 };
    }
    panic!("no {count} free ports in a row below the ephemeral range");
}

/// Reads `child`'s stderr until a line contains `needle` (that line) or the stream ends
/// (`None`); a thread goes on draining the rest.
pub fn stderr_lines_until(child: &mut Child, needle: &str) -> Option<String> {
    use std::io::BufRead as _;
    let stderr = child.stderr.take().expect("stderr is piped");
    let (found, said) = crossbeam_channel::bounded(1);
    let needle = needle.to_owned();
    std::thread::spawn(move || {
        for line in std::io::BufReader::new(stderr).lines() {
            let Ok(line) = line else { break };
            if line.contains(&needle) {
                found.try_send(line).ok();
            }
        }
    });
    said.recv_timeout(Duration::from_secs(30)).ok()
}
