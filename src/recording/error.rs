//! What can go wrong on the recording side: a destination that cannot be opened (the user's
//! to fix, so each says what would work), and a recording that cannot be written.

use std::net::SocketAddr;
use std::path::PathBuf;

/// What could not be opened, and what would work.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    #[error(
        "the Rerun viewer is not installed: install it with `pip install rerun-sdk==0.36.3`, or save the recording with --save FILE.rrd and open it later"
    )]
    ViewerNotInstalled,
    #[error("could not start the Rerun viewer: {0}")]
    Spawn(rerun::SpawnError),
    #[error(
        "connect = {url}: {reason}; expected rerun+http://HOST:PORT/proxy (the viewer prints its address)"
    )]
    ConnectUrl { url: String, reason: String },
    #[error(
        "connect = {url}: no viewer is listening there (the connection was refused); start one with `rerun`, or add --save FILE.rrd to keep the run without one"
    )]
    NoViewerListening { url: String },
    #[error(
        "serve-grpc = {addr}: cannot listen there ({reason}); name a free port, e.g. --serve-grpc {}:{}",
        addr.ip(),
        addr.port().wrapping_add(1)
    )]
    ServeAddress {
        addr: SocketAddr,
        /// Not a `source`: the message says it, and the error is printed with its chain.
        reason: std::io::Error,
    },
    #[error(
        "web = {addr}: cannot serve the web viewer there ({reason}); name a free port, e.g. --web {}:{}",
        addr.ip(),
        addr.port().wrapping_add(1)
    )]
    WebAddress {
        addr: SocketAddr,
        reason: std::io::Error,
    },
    #[error("save = {path}: cannot write there ({reason})")]
    Save { path: PathBuf, reason: String },
    #[error(
        "stdout is a terminal: a recording is binary; pipe it into a viewer (`rope run --stdout | rerun -`) or use --save FILE.rrd"
    )]
    StdoutIsTerminal,
    #[error("could not open the recording")]
    Recording(#[from] rerun::RecordingStreamError),
    #[error("could not start a thread: {0}")]
    Thread(std::io::Error),
}

/// Why frames could not be written to the recording.
#[derive(Debug, thiserror::Error)]
pub enum RecordingError {
    #[error(transparent)]
    Log(#[from] rerun::RecordingStreamError),
    #[error(transparent)]
    Serialize(#[from] rerun::SerializationError),
    #[error(transparent)]
    Flush(#[from] rerun::sink::SinkFlushError),
}
