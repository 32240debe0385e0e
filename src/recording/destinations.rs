//! Where a run's recording goes: a spawned or connected viewer, a gRPC endpoint hosted in
//! this process that viewers join at any time, an `.rrd` file, stdout, or several at once
//! (`--spawn --save FILE` watches and keeps the run).
//!
//! This replaces `rerun::clap::RerunArgs`, which picks exactly one destination (`--save`
//! silently wins over `--spawn`), binds its server to 0.0.0.0, and has no way to learn that
//! a viewer has gone.

use super::error::OutputError;
use super::live::HistoryRates;
use super::memory::InMemory;
use super::viewer_sinks::{LiveDropped, LiveSink, ServedSink, ViewerLink, ViewerSink};
use rerun::RecordingStream;
use rerun::blueprint::Blueprint;
use rerun::sink::LogSink;
use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// Rerun's default port, for `--connect` and `--serve-grpc`.
pub const DEFAULT_PORT: u16 = 9876;

/// What `--server-memory-limit` is when not given.
pub const DEFAULT_SERVER_MEMORY_LIMIT: &str = "512MB";

/// Rerun's server counts its history in encoded message bytes; the process holds 1.35 to 1.5
/// times that (measured with `scripts/soak.sh`: 39.5 MB resident for a 20 MB history, about 700 MB
/// for 512 MB). The server is given what keeps the whole process within the user's limit.
const HISTORY_OVERHEAD: f64 = 1.5;

/// What the process needs besides the history (about 10 MB measured), with room to spare.
const PROCESS_BASELINE: u64 = 32_000_000;

/// The smallest `--server-memory-limit` that leaves the history room.
const MIN_SERVER_MEMORY: u64 = 64_000_000;

/// Where the web viewer's page is served when `--web` names no address.
pub const DEFAULT_WEB_PORT: u16 = 9090;

/// Where the recording goes.
#[derive(Clone, Debug, clap::Args)]
#[command(group(clap::ArgGroup::new("served").args(["serve_grpc", "web"]).multiple(true)))]
pub struct OutputArgs {
    /// Start a Rerun viewer and stream to it; the default when no other destination is given.
    /// With --save, the viewer shows the run while the file keeps it.
    #[arg(long)]
    pub spawn: bool,

    /// Stream to a running viewer at URL [default: rerun+http://127.0.0.1:9876/proxy]. If it
    /// goes away the run stops within seconds, or goes on when --save is also given.
    #[arg(long, value_name = "URL", num_args = 0..=1, default_missing_value = "rerun+http://127.0.0.1:9876/proxy", value_parser = parse_connect_url, conflicts_with_all = ["spawn", "serve_grpc"])]
    pub connect: Option<String>,

    /// Host Rerun's gRPC endpoint in this process, so any number of viewers can join at any
    /// time with `rerun --connect rerun+http://ADDR/proxy`, late ones getting the recent
    /// history. ADDR is IP:PORT, IP or PORT [default: 127.0.0.1:9876]; name 0.0.0.0 to be
    /// reachable from other machines. A finite run keeps serving until Ctrl-C.
    #[arg(long, value_name = "ADDR", num_args = 0..=1, default_missing_value = "127.0.0.1:9876", value_parser = parse_serve_addr, conflicts_with = "spawn")]
    pub serve_grpc: Option<SocketAddr>,

    /// Serve Rerun's web viewer at ADDR (IP:PORT, IP or PORT) [default: 127.0.0.1:9090], the
    /// run streaming to it: watch in a browser, with nothing to install. Implies --serve-grpc
    /// on the same IP (port 9876 unless --serve-grpc names one). Opens a browser where one
    /// can open.
    #[arg(long, value_name = "ADDR", num_args = 0..=1, default_missing_value = "127.0.0.1:9090", value_parser = parse_web_addr, conflicts_with_all = ["spawn", "connect"])]
    pub web: Option<SocketAddr>,

    /// With --web: print the page's address, and open no browser.
    #[arg(long, requires = "web")]
    pub no_browser: bool,

    /// Memory the --serve-grpc process may use, its history for late viewers included, e.g.
    /// 512MB, 2GB or 10% (of the machine's memory); beyond it the oldest data is dropped.
    #[arg(long, value_name = "SIZE", default_value = DEFAULT_SERVER_MEMORY_LIMIT, value_parser = parse_memory_limit, requires = "served")]
    pub server_memory_limit: ServerMemoryLimit,

    /// For viewers of a served, endless or looping run, which get a live picture and a
    /// history: rows of the time series the history keeps per time unit; the rope's shape
    /// is kept at a third of that rate. The run prints how long a browser page can stay open
    /// at this rate. A --save file keeps every frame whatever this says.
    #[arg(long, value_name = "ROWS", default_value_t = HistoryRates::DEFAULT.series_per_unit, value_parser = parse_history_rate)]
    pub history_rate: f64,

    /// Write the recording to FILE.rrd (as well as to a viewer, if one is named).
    #[arg(long, value_name = "FILE.rrd")]
    pub save: Option<PathBuf>,

    /// Write the recording to standard output, to pipe into a viewer (`| rerun -`).
    #[arg(long, short = 'o', conflicts_with_all = ["spawn", "connect", "serve_grpc", "web", "save"])]
    pub stdout: bool,

    /// A destination in memory, for a caller in the same process (a test): it gets the
    /// recording of every frame, as a file would. Not a flag.
    #[arg(skip)]
    pub memory: Option<InMemory>,
}

/// What a run logs into: a recording that keeps every frame, or, for viewers of a run that
/// never ends, two streams of one recording (see [`super::live`]).
pub enum Recording {
    Everything(RecordingStream),
    Live {
        history: RecordingStream,
        live: RecordingStream,
    },
}

/// The blueprints a run's recordings open with: one for a recording of every frame, one for
/// a live picture beside its history.
pub struct Layouts {
    pub everything: Blueprint,
    pub live: Blueprint,
}

/// Open recordings and what is attached to them.
pub struct Output {
    /// A file (or stdout) and every viewer: one recording of every frame; or, for viewers of
    /// a run that never ends, their live picture and history, and the file's recording of
    /// every frame beside them.
    pub recordings: Vec<Recording>,
    /// The viewer streamed to (spawned or connected), to watch for its loss.
    pub viewer: Option<ViewerLink>,
    /// Where viewers can join, when serving: the history's endpoint, and the live
    /// picture's when it has one of its own.
    pub serving: Option<String>,
    pub serving_live: Option<String>,
    /// Whether the recording outlives a lost viewer (a file or a served endpoint is kept).
    pub survives_viewer_loss: bool,
    /// The web viewer's page, with the stream's address in it, when `--web` serves one.
    pub web_page: Option<String>,
    /// Live pictures not sent because a served viewer was behind.
    pub live_dropped: Option<LiveDropped>,
    /// The web viewer's HTTP server: it serves for as long as this is kept.
    _web_server: Option<Box<dyn std::any::Any>>,
}

impl OutputArgs {
    /// What the history of viewers of a run that never ends keeps.
    pub fn history_rates(&self) -> HistoryRates {
        HistoryRates::at(self.history_rate)
    }

    /// The `--save` file's name when it does not end in `.rrd` (it is a Rerun recording
    /// whatever its name, but tools go by the name): the caller warns of it.
    pub fn misnamed_file(&self) -> Option<&std::path::Path> {
        self.save
            .as_deref()
            .filter(|path| path.extension().is_none_or(|e| e != "rrd"))
    }

    /// Whether viewers get a live picture and a history rather than every frame: for a run
    /// that is served, or that never ends (`endless`) and has a viewer.
    pub fn live(&self, endless: bool) -> bool {
        self.served_at().is_some()
            || (endless && (self.connect.is_some() || self.spawn || self.nothing_named()))
    }

    /// Opens every destination named (or spawns a viewer when none is) and the recordings
    /// that send to them; `endless`: the run never ends by itself (`--duration inf`,
    /// `--loop`).
    pub fn open(
        &self,
        application_id: &'static str,
        layouts: Layouts,
        endless: bool,
    ) -> Result<Output, OutputError> {
        if !self.live(endless) {
            return self.open_everything(application_id, layouts.everything);
        }
        let files = self.file_sinks()?;
        let survives_viewer_loss = !files.is_empty() || self.served_at().is_some();
        let mut history: Vec<Box<dyn LogSink>> = Vec::new();
        let mut live: Vec<Box<dyn LogSink>> = Vec::new();
        let viewer = self.viewer(survives_viewer_loss, &mut history)?;
        if let Some(link) = &viewer
            && link.lost().is_none()
        {
            // The same viewer, over a connection of its own that shares the history's link.
            live.push(Box::new(ViewerSink::connect_beside(link)?));
        }
        let (mut serving, mut serving_live, mut live_dropped) = (None, None, None);
        let (mut web_page, mut web_server) = (None, None);
        if let Some(addr) = self.served_at() {
            history.push(Box::new(ServedSink::new(
                self.serve(addr, history_limit(self.server_memory_limit.limit))?,
            )));
            let live_addr = SocketAddr::new(addr.ip(), addr.port().wrapping_add(1));
            let sink = LiveSink::new(self.serve(live_addr, rerun::MemoryLimit::from_bytes(0))?)
                .map_err(OutputError::Thread)?;
            live_dropped = Some(sink.dropped());
            live.push(Box::new(sink));
            let urls = [addr, live_addr].map(|a| format!("rerun+http://{a}/proxy"));
            if let Some(web) = self.web {
                let (page, server) = self.host_web_viewer(web, &urls)?;
                web_page = Some(page);
                web_server = Some(server);
            }
            let [history_url, live_url] = urls;
            serving = Some(history_url);
            serving_live = Some(live_url);
        }
        let id = fresh_recording_id();
        let history = rerun::RecordingStreamBuilder::new(application_id)
            .recording_id(id.clone())
            .with_blueprint(layouts.live)
            .batcher_config(rerun::log::ChunkBatcherConfig::LOW_LATENCY)
            .set_sinks(history)?;
        let live = rerun::RecordingStreamBuilder::new(application_id)
            .recording_id(id)
            .batcher_config(rerun::log::ChunkBatcherConfig::LOW_LATENCY)
            .set_sinks(live)?;
        let mut recordings = vec![Recording::Live { history, live }];
        if !files.is_empty() {
            let file = rerun::RecordingStreamBuilder::new(application_id)
                .with_blueprint(layouts.everything)
                .set_sinks(files)?;
            recordings.insert(0, Recording::Everything(file));
        }
        Ok(Output {
            recordings,
            viewer,
            serving,
            serving_live,
            survives_viewer_loss,
            web_page,
            live_dropped,
            _web_server: web_server,
        })
    }

    /// One recording of every frame, sent to every destination.
    fn open_everything(
        &self,
        application_id: &'static str,
        blueprint: Blueprint,
    ) -> Result<Output, OutputError> {
        let mut sinks = self.file_sinks()?;
        let survives_viewer_loss = self.save.is_some() || self.memory.is_some();
        let viewer = self.viewer(survives_viewer_loss, &mut sinks)?;
        let mut builder =
            rerun::RecordingStreamBuilder::new(application_id).with_blueprint(blueprint);
        if viewer.is_some() {
            // Live viewers want data as it happens, not in the file sink's larger batches.
            builder = builder.batcher_config(rerun::log::ChunkBatcherConfig::LOW_LATENCY);
        }
        let rec = builder.set_sinks(sinks)?;
        Ok(Output {
            recordings: vec![Recording::Everything(rec)],
            viewer,
            serving: None,
            serving_live: None,
            survives_viewer_loss,
            web_page: None,
            live_dropped: None,
            _web_server: None,
        })
    }

    /// Where the gRPC endpoint is hosted: `--serve-grpc`, or for `--web` alone the page's IP
    /// at Rerun's default port.
    pub fn served_at(&self) -> Option<SocketAddr> {
        self.serve_grpc
            .or_else(|| self.web.map(|web| SocketAddr::new(web.ip(), DEFAULT_PORT)))
    }

    /// Serves Rerun's web viewer at `addr`, streaming from the endpoint at `stream`; returns
    /// the page's address (with the stream in it) and the server, which serves while kept.
    fn host_web_viewer(
        &self,
        addr: SocketAddr,
        streams: &[String],
    ) -> Result<(String, Box<dyn std::any::Any>), OutputError> {
        let refuse = |reason| OutputError::WebAddress { addr, reason };
        std::net::TcpListener::bind(addr).map_err(refuse)?;
        let server = rerun::serve_web_viewer(rerun::web_viewer::WebViewerConfig {
            bind_ip: addr.ip().to_string(),
            web_port: addr.port().into(),
            connect_to: streams.to_vec(),
            open_browser: !self.no_browser && a_browser_can_open(),
            ..Default::default()
        })
        .map_err(|err| refuse(std::io::Error::other(err.to_string())))?;
        let query: Vec<String> = streams
            .iter()
            .map(|s| format!("url={}", url_encoded(s)))
            .collect();
        let page = format!("{}/?{}", server.server_url(), query.join("&"));
        Ok((page, Box::new(server)))
    }

    /// `--stdout` and `--save FILE`.
    fn file_sinks(&self) -> Result<Vec<Box<dyn LogSink>>, OutputError> {
        let mut sinks: Vec<Box<dyn LogSink>> = Vec::new();
        if self.stdout {
            if std::io::IsTerminal::is_terminal(&std::io::stdout()) {
                return Err(OutputError::StdoutIsTerminal);
            }
            let sink = rerun::sink::FileSink::stdout().map_err(|err| OutputError::Save {
                path: "-".into(),
                reason: err.to_string(),
            })?;
            sinks.push(Box::new(sink));
        }
        if let Some(path) = &self.save {
            let sink = rerun::sink::FileSink::new(path).map_err(|err| OutputError::Save {
                path: path.clone(),
                reason: err.to_string(),
            })?;
            sinks.push(Box::new(sink));
        }
        if let Some(memory) = &self.memory {
            sinks.push(Box::new(memory.sink()));
        }
        Ok(sinks)
    }

    /// `--connect URL`, or `--spawn` (also when nothing else is named): the viewer's sink
    /// joins `sinks`, and its link is returned to watch. A viewer that refuses the connection
    /// is an error, unless the recording is `kept` without it: then its link is lost from
    /// the start, and the run goes on.
    fn viewer(
        &self,
        kept: bool,
        sinks: &mut Vec<Box<dyn LogSink>>,
    ) -> Result<Option<ViewerLink>, OutputError> {
        let url = match (&self.connect, self.spawn || self.nothing_named()) {
            (Some(url), _) => url.clone(),
            (None, true) => spawn_viewer()?,
            (None, false) => return Ok(None),
        };
        match ViewerSink::connect(&url) {
            Ok(sink) => {
                let link = sink.link();
                sinks.push(Box::new(sink));
                Ok(Some(link))
            }
            Err(OutputError::NoViewerListening { url }) if kept => {
                Ok(Some(ViewerLink::refused(&url)))
            }
            Err(err) => Err(err),
        }
    }

    fn nothing_named(&self) -> bool {
        !self.stdout
            && self.save.is_none()
            && self.memory.is_none()
            && self.connect.is_none()
            && self.served_at().is_none()
    }

    /// Hosts a gRPC endpoint that keeps `memory_limit` of history for late viewers, after
    /// checking that its address is free (Rerun's server would only log a bind failure on
    /// its own thread, and the run would go on unseen).
    fn serve(
        &self,
        addr: SocketAddr,
        memory_limit: rerun::MemoryLimit,
    ) -> Result<rerun::grpc_server::GrpcServerSink, OutputError> {
        std::net::TcpListener::bind(addr)
            .map_err(|reason| OutputError::ServeAddress { addr, reason })?;
        let ip = match addr.ip() {
            IpAddr::V4(ip) => ip.to_string(),
            IpAddr::V6(ip) => format!("[{ip}]"),
        };
        let server = rerun::grpc_server::GrpcServerSink::new(
            &ip,
            addr.port(),
            rerun::ServerOptions {
                playback_behavior: rerun::PlaybackBehavior::OldestFirst,
                memory_limit,
                cors_allowed_origins: self.page_origins(),
            },
        )
        .map_err(|err| OutputError::ServeAddress {
            addr,
            reason: std::io::Error::new(std::io::ErrorKind::InvalidInput, err),
        })?;
        wait_until_listening(addr).map_err(|reason| OutputError::ServeAddress { addr, reason })?;
        Ok(server)
    }

    /// Origins besides Rerun's defaults (localhost, 127.0.0.1, rerun.io) that the endpoint
    /// must let a page stream from: the web viewer's own, when it is served elsewhere.
    fn page_origins(&self) -> Vec<String> {
        match self.web {
            Some(web) if !web.ip().is_loopback() => vec![format!("http://{web}")],
            _ => Vec::new(),
        }
    }
}

/// Whether a browser can be opened here: on Linux and the BSDs only with a display.
fn a_browser_can_open() -> bool {
    if cfg!(any(target_os = "macos", target_os = "windows")) {
        return true;
    }
    ["DISPLAY", "WAYLAND_DISPLAY"]
        .iter()
        .any(|v| std::env::var_os(v).is_some_and(|d| !d.is_empty()))
}

/// `text` with everything but letters, digits and `-._~` percent-encoded, for a URL's query.
fn url_encoded(text: &str) -> String {
    text.bytes()
        .map(|b| match b {
            b'a'..=b'z' | b'A'..=b'Z' | b'0'..=b'9' | b'-' | b'.' | b'_' | b'~' => {
                (b as char).to_string()
            }
            _ => format!("%{b:02X}"),
        })
        .collect()
}

/// A recording id for the two streams of one recording (a live picture and its history),
/// unique to this process and moment.
fn fresh_recording_id() -> String {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos());
    format!("rope-{}-{nanos}", std::process::id())
}

/// How long Rerun's server may take to start listening.
const SERVER_START: Duration = Duration::from_secs(10);

/// Waits until something listens at `addr` (Rerun's server binds on a thread of its own), so
/// that "serving at …" is only said once a viewer can connect.
fn wait_until_listening(addr: SocketAddr) -> std::io::Result<()> {
    let mut target = addr;
    if target.ip().is_unspecified() {
        target.set_ip(match addr.ip() {
            IpAddr::V4(_) => IpAddr::V4(Ipv4Addr::LOCALHOST),
            IpAddr::V6(_) => IpAddr::V6(std::net::Ipv6Addr::LOCALHOST),
        });
    }
    let started = Instant::now();
    loop {
        match std::net::TcpStream::connect_timeout(&target, Duration::from_secs(1)) {
            Ok(_) => return Ok(()),
            Err(err) if started.elapsed() > SERVER_START => {
                return Err(std::io::Error::new(
                    err.kind(),
                    format!(
                        "the server did not start listening within {} s ({err})",
                        SERVER_START.as_secs()
                    ),
                ));
            }
            Err(_) => std::thread::sleep(Duration::from_millis(10)),
        }
    }
}

/// The history limit to give Rerun's server so that the process stays within `process_limit`.
fn history_limit(process_limit: rerun::MemoryLimit) -> rerun::MemoryLimit {
    if process_limit.is_unlimited() {
        return process_limit;
    }
    let room = process_limit.as_bytes().saturating_sub(PROCESS_BASELINE);
    rerun::MemoryLimit::from_bytes((room as f64 / HISTORY_OVERHEAD) as u64)
}

/// Starts a viewer (or finds one already listening on the default port) and returns its URL.
fn spawn_viewer() -> Result<String, OutputError> {
    match rerun::spawn(&rerun::SpawnOptions::default()) {
        Ok(spawned) => Ok(format!(
            "rerun+http://{}/proxy",
            SocketAddr::new(IpAddr::V4(Ipv4Addr::LOCALHOST), spawned.port)
        )),
        Err(rerun::SpawnError::ExecutableNotFoundInPath { .. }) => {
            Err(OutputError::ViewerNotInstalled)
        }
        Err(err) => Err(OutputError::Spawn(err)),
    }
}

/// `--connect URL`: a Rerun proxy URL.
fn parse_connect_url(url: &str) -> Result<String, String> {
    match url.parse::<rerun::external::re_uri::RedapUri>() {
        Ok(rerun::external::re_uri::RedapUri::Proxy(_)) => Ok(url.to_owned()),
        Ok(_) => Err(format!(
            "{url} is not a viewer's /proxy endpoint; expected rerun+http://HOST:PORT/proxy"
        )),
        Err(err) => Err(format!(
            "{err}; expected rerun+http://HOST:PORT/proxy (the viewer prints its address)"
        )),
    }
}

/// `--serve-grpc ADDR`: IP:PORT, IP (port 9876) or PORT (on 127.0.0.1).
pub fn parse_serve_addr(text: &str) -> Result<SocketAddr, String> {
    parse_addr(text, DEFAULT_PORT)
}

/// `--web ADDR`: IP:PORT, IP (port 9090) or PORT (on 127.0.0.1).
pub fn parse_web_addr(text: &str) -> Result<SocketAddr, String> {
    parse_addr(text, DEFAULT_WEB_PORT)
}

/// IP:PORT, IP (at `default_port`) or PORT (on 127.0.0.1).
fn parse_addr(text: &str, default_port: u16) -> Result<SocketAddr, String> {
    if let Ok(addr) = text.parse::<SocketAddr>() {
        return Ok(addr);
    }
    if let Ok(ip) = text.parse::<IpAddr>() {
        return Ok(SocketAddr::new(ip, default_port));
    }
    if let Ok(port) = text.trim_start_matches(':').parse::<u16>() {
        return Ok(SocketAddr::new(IpAddr::V4(Ipv4Addr::LOCALHOST), port));
    }
    Err(format!(
        "{text:?} is not an address; give IP:PORT (127.0.0.1:9876), an IP (0.0.0.0 for every interface) or a PORT"
    ))
}

/// `--history-rate ROWS`: a positive, finite number of rows per time unit.
fn parse_history_rate(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(rate) if rate.is_finite() && rate > 0.0 && rate <= 1e4 => Ok(rate),
        _ => Err(format!(
            "{text}: give the rows of time series kept per time unit, a number above 0 (1.5 keeps about 10 days in a browser page; at most 10000)"
        )),
    }
}

/// `--server-memory-limit SIZE`: the limit, and the words the user gave it in.
#[derive(Clone, Debug)]
pub struct ServerMemoryLimit {
    text: String,
    limit: rerun::MemoryLimit,
}

impl std::fmt::Display for ServerMemoryLimit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.text)
    }
}

/// `--server-memory-limit SIZE`.
fn parse_memory_limit(text: &str) -> Result<ServerMemoryLimit, String> {
    match rerun::MemoryLimit::parse(&crate::run::cost::size_spelling(text)) {
        Ok(limit) if limit.as_bytes() >= MIN_SERVER_MEMORY => Ok(ServerMemoryLimit {
            text: text.to_owned(),
            limit,
        }),
        Ok(_) => Err(format!(
            "{text}: the process needs about {} MB besides the served history; give at least 64MB",
            PROCESS_BASELINE / 1_000_000
        )),
        Err(err) => Err(format!("{err}; give e.g. 512MB, 2GB or 10%")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn serve_address_defaults_to_loopback_and_port_9876() {
        assert_eq!(
            parse_serve_addr("127.0.0.1:9000").unwrap(),
            "127.0.0.1:9000".parse().unwrap()
        );
        assert_eq!(
            parse_serve_addr("0.0.0.0").unwrap(),
            "0.0.0.0:9876".parse().unwrap()
        );
        assert_eq!(
            parse_serve_addr("9001").unwrap(),
            "127.0.0.1:9001".parse().unwrap()
        );
        assert_eq!(
            parse_serve_addr("::1").unwrap(),
            "[::1]:9876".parse().unwrap()
        );
        assert!(parse_serve_addr("localhost:x").is_err());
    }

    #[test]
    fn the_history_gets_what_leaves_the_process_within_its_limit() {
        let limit = |text| parse_memory_limit(text).unwrap().limit;
        assert_eq!(history_limit(limit("512MB")).as_bytes(), 320_000_000);
        assert!(history_limit(limit("unlimited")).is_unlimited());
    }

    #[test]
    fn memory_limits_parse_like_rerun_and_refuse_too_little() {
        assert!(parse_memory_limit("512MB").is_ok());
        assert!(parse_memory_limit("10%").is_ok());
        assert!(parse_memory_limit("0").is_err());
        assert!(parse_memory_limit("20MB").is_err());
        assert!(parse_memory_limit("lots").is_err());
    }
}
