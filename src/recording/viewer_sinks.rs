//! Links to viewers that can never stall a run or its exit: [`ViewerSink`] to a viewer this
//! process connects to, [`ServedSink`] for the endpoint viewers connect to.
//!
//! Rerun's [`GrpcSink`] blocks the caller while a viewer cannot take data (its queue holds
//! 100 messages), retries a connection forever, and waits without a bound for a viewer to
//! take the last data when it is dropped. For a process meant to run for hours beside viewers
//! that come and go, [`ViewerSink`] puts a thread and a bounded queue in front of it: once the
//! viewer is gone (disconnected, never answered, or took nothing for [`STALL`]) every further
//! message is dropped at once, and [`ViewerLink`] says why, so the caller can stop or go on.
//!
//! The reason a viewer is gone depends only on what happened, never on which thread saw it
//! first: a viewer that never accepted the connection is "no viewer answered at …", however
//! that showed (refused, grace over, a flush that timed out, a dropped connection attempt);
//! one that had accepted it went away, or took no data.

use super::error::OutputError;
use crossbeam_channel::{Receiver, RecvTimeoutError, SendTimeoutError, Sender};
use rerun::log::{ChunkBatcherConfig, LogMsg};
use rerun::sink::{GrpcSink, GrpcSinkConnectionState, LogSink, SinkFlushError};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::{Duration, Instant};

/// How long a viewer may take to accept the connection.
pub const CONNECT_GRACE: Duration = Duration::from_secs(5);

/// How long a connected viewer may take no data at all before it counts as gone.
pub const STALL: Duration = Duration::from_secs(5);

/// The longest any flush waits for the viewer: less than the recording's own flush timeout
/// (5 s), so that a viewer that cannot take the data is always reported as such, never as
/// the recording's timeout.
pub const FLUSH_CAP: Duration = Duration::from_secs(4);

/// How much sooner than the caller the forwarding thread gives up on Rerun's client, so that
/// its answer (and its reason) always arrives while the caller still waits.
const FLUSH_MARGIN: Duration = Duration::from_secs(1);

/// Messages queued in front of Rerun's own queue: room for a viewer's hiccups.
const QUEUE: usize = 1024;

/// How often the forwarding thread looks at the connection while idle.
const POLL: Duration = Duration::from_millis(100);

/// The state of the link, shared between the sink and whoever watches it.
#[derive(Clone, Debug, PartialEq)]
enum State {
    Connecting { since: Instant },
    Connected,
    Lost(String),
}

/// A handle to watch a [`ViewerSink`]: where it points and whether the viewer is still there.
#[derive(Clone, Debug)]
pub struct ViewerLink {
    shared: Arc<Shared>,
}

#[derive(Debug)]
struct Shared {
    url: String,
    state: Mutex<State>,
}

impl ViewerLink {
    fn new(url: &str) -> Self {
        Self {
            shared: Arc::new(Shared {
                url: url.to_owned(),
                state: Mutex::new(State::Connecting {
                    since: Instant::now(),
                }),
            }),
        }
    }

    /// A link to a viewer that refused the connection: lost from the start.
    pub fn refused(url: &str) -> Self {
        let link = Self::new(url);
        *link.state() = State::Lost(format!(
            "no viewer answered at {url} (the connection was refused)"
        ));
        link
    }

    /// The viewer's address.
    pub fn url(&self) -> &str {
        &self.shared.url
    }

    /// `None` while the viewer is there (or still within [`CONNECT_GRACE`] of coming up);
    /// once it is gone, why. A lost link stays lost.
    pub fn lost(&self) -> Option<String> {
        let mut state = self.state();
        if let State::Connecting { since } = *state
            && since.elapsed() > CONNECT_GRACE
        {
            *state = State::Lost(self.no_answer());
        }
        match &*state {
            State::Lost(reason) => Some(reason.clone()),
            _ => None,
        }
    }

    /// Why a viewer that never accepted the connection counts as gone.
    fn no_answer(&self) -> String {
        format!(
            "no viewer answered at {} within {} s",
            self.url(),
            CONNECT_GRACE.as_secs()
        )
    }

    /// Why a connected viewer that a flush waited `wait` for counts as gone.
    fn did_not_take_the_data(&self, wait: Duration) -> String {
        format!(
            "the viewer at {} did not take the data within {} s",
            self.url(),
            wait.as_secs_f64()
        )
    }

    /// The viewer is gone: if it had accepted the connection, for `reason`; if it never
    /// had, because no viewer answered (whatever showed it first).
    fn lose_with(&self, reason: impl FnOnce() -> String) {
        let mut state = self.state();
        *state = match &*state {
            State::Lost(_) => return,
            State::Connecting { .. } => State::Lost(self.no_answer()),
            State::Connected => State::Lost(reason()),
        };
    }

    fn state(&self) -> std::sync::MutexGuard<'_, State> {
        self.shared
            .state
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
    }

    /// Takes in what Rerun's client reports.
    fn observe(&self, status: GrpcSinkConnectionState) {
        match status {
            GrpcSinkConnectionState::Connecting { .. } => {}
            GrpcSinkConnectionState::Connected => {
                let mut state = self.state();
                if matches!(*state, State::Connecting { .. }) {
                    *state = State::Connected;
                }
            }
            GrpcSinkConnectionState::Disconnected(Ok(())) => {
                self.lose_with(|| format!("the viewer at {} closed the connection", self.url()));
            }
            GrpcSinkConnectionState::Disconnected(Err(err)) => {
                self.lose_with(|| format!("the viewer at {} went away: {err}", self.url()));
            }
        }
    }
}

enum Command {
    Message(LogMsg),
    /// Flush Rerun's client, waiting for it at most this long; answer when done.
    Flush(Duration, Sender<()>),
}

/// A [`LogSink`] that sends to a viewer over gRPC and never blocks for longer than
/// [`STALL`] on a message, nor [`FLUSH_CAP`] on a flush or on being dropped.
pub struct ViewerSink {
    commands: Option<Sender<Command>>,
    link: ViewerLink,
    finished: Receiver<()>,
}

impl ViewerSink {
    /// Connects to the viewer at `url` (`rerun+http://host:port/proxy`).
    pub fn connect(url: &str) -> Result<Self, OutputError> {
        Self::connect_linked(url, None, QUEUE)
    }

    /// A second connection to the viewer of `link` (a live picture beside its history),
    /// sharing the link: the viewer is gone when either connection finds it gone, and then
    /// both drop their data. Its queue holds a few pictures: a live picture that waits is
    /// stale, and a viewer that takes none is found out as soon as with every frame.
    pub fn connect_beside(link: &ViewerLink) -> Result<Self, OutputError> {
        Self::connect_linked(link.url(), Some(link.clone()), LIVE_QUEUE)
    }

    fn connect_linked(
        url: &str,
        shared: Option<ViewerLink>,
        queue_length: usize,
    ) -> Result<Self, OutputError> {
        let bad_url = |reason: String| OutputError::ConnectUrl {
            url: url.to_owned(),
            reason,
        };
        let uri = match url.parse() {
            Ok(rerun::external::re_uri::RedapUri::Proxy(uri)) => uri,
            Ok(_) => return Err(bad_url("not a `/proxy` endpoint".to_owned())),
            Err(err) => return Err(bad_url(err.to_string())),
        };
        if probe(&uri.origin) == Probe::Refused {
            return Err(OutputError::NoViewerListening {
                url: url.to_owned(),
            });
        }
        let link = shared.unwrap_or_else(|| ViewerLink::new(url));
        let (commands, queue) = crossbeam_channel::bounded(queue_length);
        let (done, finished) = crossbeam_channel::bounded(1);
        let watched = link.clone();
        std::thread::Builder::new()
            .name("rope_viewer_link".to_owned())
            .spawn(move || {
                forward(GrpcSink::new(uri), &queue, &watched);
                done.send(()).ok();
            })
            .map_err(OutputError::Thread)?;
        Ok(Self {
            commands: Some(commands),
            link,
            finished,
        })
    }

    /// A handle to watch the link with.
    pub fn link(&self) -> ViewerLink {
        self.link.clone()
    }
}

/// What a plain TCP connection to a viewer's address found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Probe {
    /// Something listens there (a viewer, or one still coming up).
    Open,
    /// Every address refused the connection: nothing listens there.
    Refused,
    /// Neither could be told (a name that does not resolve, a network that does not
    /// answer); Rerun's client finds out, within [`CONNECT_GRACE`].
    Unknown,
}

/// Whether anything listens at `origin`: a refused connection is known at once, so a run
/// need not wait out the connect grace to learn that no viewer is there.
fn probe(origin: &rerun::external::re_uri::Origin) -> Probe {
    use std::net::ToSocketAddrs as _;
    let host = origin.format_host();
    let host = host.trim_start_matches('[').trim_end_matches(']');
    let Ok(addrs) = (host, origin.port).to_socket_addrs() else {
        return Probe::Unknown;
    };
    let mut refused = false;
    for addr in addrs {
        match std::net::TcpStream::connect_timeout(&addr, PROBE_TIMEOUT) {
            Ok(_) => return Probe::Open,
            Err(err) if err.kind() == std::io::ErrorKind::ConnectionRefused => refused = true,
            Err(_) => return Probe::Unknown,
        }
    }
    if refused {
        Probe::Refused
    } else {
        Probe::Unknown
    }
}

/// How long the probe waits for an answer before leaving it to Rerun's client.
const PROBE_TIMEOUT: Duration = Duration::from_secs(1);

/// The forwarding thread: hands the queue to Rerun's client while the viewer is there.
fn forward(sink: GrpcSink, queue: &Receiver<Command>, link: &ViewerLink) {
    loop {
        let command = queue.recv_timeout(POLL);
        link.observe(sink.status());
        match command {
            Ok(Command::Message(msg)) => {
                if link.lost().is_none() {
                    sink.send(msg);
                }
            }
            Ok(Command::Flush(wait, reply)) => {
                if link.lost().is_none() {
                    let result = sink.flush_blocking(wait);
                    link.observe(sink.status());
                    if result.is_err() {
                        link.lose_with(|| link.did_not_take_the_data(wait));
                    }
                }
                reply.send(()).ok();
            }
            Err(RecvTimeoutError::Timeout) => {}
            Err(RecvTimeoutError::Disconnected) => break,
        }
    }
    if link.lost().is_some() {
        // Dropping Rerun's client waits, without a bound, for the viewer to take what is
        // queued; a viewer that is gone never will. Its thread ends with the process.
        std::mem::forget(sink);
    }
}

impl LogSink for ViewerSink {
    fn send(&self, msg: LogMsg) {
        let Some(commands) = &self.commands else {
            return;
        };
        if self.link.lost().is_some() {
            return; // dropped: the viewer is gone
        }
        // A viewer still coming up gets what is left of its grace; a connected one, STALL.
        let patience = match *self.link.state() {
            State::Connecting { since } => CONNECT_GRACE.saturating_sub(since.elapsed()),
            _ => STALL,
        };
        match commands.send_timeout(Command::Message(msg), patience) {
            Ok(()) => {}
            Err(SendTimeoutError::Timeout(_)) => {
                self.link.lose_with(|| {
                    format!(
                        "the viewer at {} took no data for {} s",
                        self.link.url(),
                        STALL.as_secs()
                    )
                });
            }
            Err(SendTimeoutError::Disconnected(_)) => {}
        }
    }

    /// Waits (at most [`FLUSH_CAP`]) for the viewer to take everything sent so far. Never
    /// fails: a viewer that cannot take it is marked lost, and the link reports that, once.
    fn flush_blocking(&self, timeout: Duration) -> Result<(), SinkFlushError> {
        let Some(commands) = &self.commands else {
            return Ok(());
        };
        if self.link.lost().is_some() {
            return Ok(());
        }
        let timeout = timeout.min(FLUSH_CAP);
        let wait = timeout.saturating_sub(FLUSH_MARGIN);
        let started = Instant::now();
        let (reply, answer) = crossbeam_channel::bounded(1);
        let answered = commands
            .send_timeout(Command::Flush(wait, reply), timeout)
            .ok()
            .and_then(|()| {
                answer
                    .recv_timeout(timeout.saturating_sub(started.elapsed()))
                    .ok()
            });
        if answered.is_none() {
            // The forwarding thread is stuck handing over messages the viewer does not take.
            self.link
                .lose_with(|| self.link.did_not_take_the_data(wait));
        }
        Ok(())
    }

    fn default_batcher_config(&self) -> ChunkBatcherConfig {
        ChunkBatcherConfig::LOW_LATENCY
    }
}

impl Drop for ViewerSink {
    fn drop(&mut self) {
        // Closing the queue ends the forwarding thread once it has handed everything over;
        // it gets FLUSH_CAP (and a little) to do so, and is left behind after that, or at
        // once when the viewer is known to be gone.
        self.commands = None;
        if self.link.lost().is_none() {
            self.finished.recv_timeout(FLUSH_CAP + POLL * 2).ok();
        }
    }
}

/// How long the end of a run, or of the process, waits for a served endpoint's viewers.
pub const SERVE_FLUSH_CAP: Duration = Duration::from_millis(500);

/// Rerun's gRPC server as a [`LogSink`] whose flush and shutdown are bounded.
///
/// A viewer that stops reading (frozen, or a laptop asleep) holds back Rerun's server until
/// its keepalive gives up on it (10 s pings, 20 s timeout), and Rerun's shutdown would wait
/// for it without a bound. The data is in the server's history either way, and a served
/// process that exits takes its viewers' connections with it; so a flush waits at most
/// [`SERVE_FLUSH_CAP`] and never fails for a slow viewer, and shutdown leaves after that.
pub struct ServedSink {
    server: Option<rerun::grpc_server::GrpcServerSink>,
}

impl ServedSink {
    /// Wraps a started server.
    pub fn new(server: rerun::grpc_server::GrpcServerSink) -> Self {
        Self {
            server: Some(server),
        }
    }
}

impl LogSink for ServedSink {
    fn send(&self, msg: LogMsg) {
        if let Some(server) = &self.server {
            server.send(msg);
        }
    }

    fn flush_blocking(&self, timeout: Duration) -> Result<(), SinkFlushError> {
        match &self.server {
            Some(server) => match server.flush_blocking(timeout.min(SERVE_FLUSH_CAP)) {
                Err(SinkFlushError::Timeout) => Ok(()), // a viewer is behind: not our loss
                other => other,
            },
            None => Ok(()),
        }
    }

    fn default_batcher_config(&self) -> ChunkBatcherConfig {
        ChunkBatcherConfig::LOW_LATENCY
    }
}

impl Drop for ServedSink {
    fn drop(&mut self) {
        let Some(server) = self.server.take() else {
            return;
        };
        let (done, finished) = crossbeam_channel::bounded(1);
        let closing = std::thread::Builder::new()
            .name("rope_served_close".to_owned())
            .spawn(move || {
                drop(server);
                done.send(()).ok();
            });
        if closing.is_ok() {
            finished.recv_timeout(SERVE_FLUSH_CAP).ok();
        }
    }
}

/// Live pictures that a [`LiveSink`] did not send because its viewers were behind.
#[derive(Clone, Debug, Default)]
pub struct LiveDropped(Arc<std::sync::atomic::AtomicU64>);

impl LiveDropped {
    /// How many messages were dropped so far.
    pub fn count(&self) -> u64 {
        self.0.load(std::sync::atomic::Ordering::Relaxed)
    }

    fn add(&self) {
        self.0.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    }
}

/// Messages of the live picture that may wait for a served endpoint: a few pictures.
const LIVE_QUEUE: usize = 64;

/// How long the live picture's thread waits for the endpoint at a time, to notice when the
/// process is closing.
const LIVE_WAIT: Duration = Duration::from_millis(500);

/// The live picture's served endpoint (one that keeps no history), as a [`LogSink`] that
/// drops pictures rather than queue them while its viewers are behind.
///
/// Rerun's server hands every message to every viewer through a bounded broadcast; a viewer
/// that reads slowly (or a page that stops reading) holds it back, and what the process
/// sends meanwhile waits in an unbounded queue. A live picture replaces itself, so nothing is
/// lost by sending fewer of them: a thread hands the server what it can take, waiting for it
/// to take each batch before the next, and messages that find the queue in front of it full
/// are dropped (and counted). The process's memory stays bounded whoever reads how slowly.
pub struct LiveSink {
    /// Closed when the sink is dropped: the thread sends what is left, then ends.
    queue: Sender<LogMsg>,
    dropped: LiveDropped,
}

impl LiveSink {
    /// Wraps a started server that keeps no history.
    pub fn new(server: rerun::grpc_server::GrpcServerSink) -> std::io::Result<Self> {
        let (queue, messages) = crossbeam_channel::bounded::<LogMsg>(LIVE_QUEUE);
        std::thread::Builder::new()
            .name("rope_live_picture".to_owned())
            .spawn(move || forward_live(server, &messages))?;
        Ok(Self {
            queue,
            dropped: LiveDropped::default(),
        })
    }

    /// A handle on the count of dropped messages.
    pub fn dropped(&self) -> LiveDropped {
        self.dropped.clone()
    }
}

/// The live picture's thread: sends what is queued, then waits until the server has taken
/// it before sending more.
fn forward_live(server: rerun::grpc_server::GrpcServerSink, messages: &Receiver<LogMsg>) {
    while let Ok(msg) = messages.recv() {
        server.send(msg);
        while let Ok(msg) = messages.try_recv() {
            server.send(msg);
        }
        loop {
            match server.flush_blocking(LIVE_WAIT) {
                Err(SinkFlushError::Timeout) if !messages.is_empty() || !closed(messages) => {}
                Err(SinkFlushError::Timeout) => {
                    // Closing while a viewer holds the server back: Rerun's shutdown would
                    // wait for it without a bound. The process takes the thread with it.
                    std::mem::forget(server);
                    return;
                }
                _ => break,
            }
        }
    }
    drop(server);
}

/// Whether nobody can send on the queue any more.
fn closed(messages: &Receiver<LogMsg>) -> bool {
    matches!(
        messages.recv_timeout(Duration::ZERO),
        Err(RecvTimeoutError::Disconnected)
    )
}

impl LogSink for LiveSink {
    fn send(&self, msg: LogMsg) {
        if self.queue.try_send(msg).is_err() {
            self.dropped.add();
        }
    }

    /// The live picture is never waited for: what a viewer has not taken is replaced.
    fn flush_blocking(&self, _timeout: Duration) -> Result<(), SinkFlushError> {
        Ok(())
    }

    fn default_batcher_config(&self) -> ChunkBatcherConfig {
        ChunkBatcherConfig::LOW_LATENCY
    }
}
