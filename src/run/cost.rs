//! What a run will cost, said before it starts: CPU time and memory from the method's own
//! cost model, and the limits a run must stay within (the machine's memory, a day of CPU
//! unless the user says yes).

use super::estimate::{STRIDE, Shadow};
use crate::methods::MethodKind;
use std::time::Duration;

/// CPU time spent on one frame, per segment: building it and logging it (measured with
/// `rope run --segments 100000 --dt 1e-7 --duration 2e-5 --log-rate 1e7 --save F`: about
/// 100 ns per segment-step with a frame at every step, against 10 for the step alone).
pub const FRAME_NS_PER_SEGMENT: f64 = 100.0;

/// Memory of the frames in flight between the simulation, the logger and Rerun, per
/// segment, at the worst (every queue full): measured with the same command, 650 MB resident
/// at N = 10⁵ and 2.25 GB at N = 4·10⁵.
pub const FRAME_BYTES_PER_SEGMENT: u64 = 6_000;

/// What the process needs whatever the size (the binary, Rerun's threads and buffers).
pub const BASE_BYTES: u64 = 64_000_000;

/// A run that needs no more than this is not checked against the machine's available memory:
/// any machine rope runs on has it, and asking (reading /proc/meminfo, about 10 µs) cost a
/// small run from 30° to t = 1 a seventh of its CPU. A `--max-memory` is still held.
pub const SURELY_AVAILABLE: u64 = 2 * BASE_BYTES;

/// A run predicted to take longer than this says so before it starts.
pub const ANNOUNCE_SECONDS: f64 = 60.0;

/// A finite run predicted to take longer than this needs `--yes`.
pub const LONG_SECONDS: f64 = 86_400.0;

/// A run's predicted CPU time and peak memory.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cost {
    /// CPU seconds; infinite for an endless run.
    pub seconds: f64,
    /// Bytes at the peak.
    pub bytes: u64,
}

impl Cost {
    /// A run of `method` at `segments` and step `dt`, to `duration`, with `log_rate` frames
    /// per time unit (0 for none).
    pub fn of_run(
        method: MethodKind,
        segments: usize,
        dt: f64,
        duration: f64,
        log_rate: f64,
    ) -> Self {
        let d = method.descriptor();
        let n = segments as f64;
        // A method that runs past its limit does so in substeps, each at most the limit.
        let effective = if d.refuses_unstable_step {
            dt
        } else {
            dt.min(d.stability_limit(segments))
        };
        let steps = (duration / effective).ceil();
        let frames = duration * log_rate + 1.0;
        let seconds = n * (steps * d.ns_per_segment_step + frames * FRAME_NS_PER_SEGMENT) * 1e-9;
        let per_segment = Self::bytes_per_segment(method, log_rate);
        Self {
            seconds,
            bytes: BASE_BYTES.saturating_add((segments as u64).saturating_mul(per_segment)),
        }
    }

    /// As [`Cost::of_run`], with the run's shadow at N/2 and twice the step (the live error
    /// estimate, `run::estimate`) if `estimate` and the run can be halved.
    pub fn of_estimated_run(
        method: MethodKind,
        segments: usize,
        dt: f64,
        duration: f64,
        log_rate: f64,
        estimate: bool,
    ) -> Self {
        let run = Self::of_run(method, segments, dt, duration, log_rate);
        if !(estimate && Shadow::possible(method, segments)) {
            return run;
        }
        let half = Shadow::segments_of(segments);
        run.with(&Self::of_run(
            method,
            half,
            dt * STRIDE as f64,
            duration,
            0.0,
        ))
    }

    /// This run and `other` side by side: their CPU times and their state added (`other`'s
    /// process overhead counted once).
    pub fn with(&self, other: &Cost) -> Self {
        Self {
            seconds: self.seconds + other.seconds,
            bytes: self
                .bytes
                .saturating_add(other.bytes.saturating_sub(BASE_BYTES)),
        }
    }

    /// The largest segment count whose memory fits in `limit` bytes, for a run like this.
    pub fn segments_within(method: MethodKind, log_rate: f64, limit: u64) -> usize {
        let per_segment = Self::bytes_per_segment(method, log_rate);
        (limit.saturating_sub(BASE_BYTES) / per_segment.max(1)) as usize
    }

    /// Memory per segment: the method's state, and the frames in flight when any are logged.
    fn bytes_per_segment(method: MethodKind, log_rate: f64) -> u64 {
        let frames = if log_rate > 0.0 {
            FRAME_BYTES_PER_SEGMENT
        } else {
            0
        };
        method.descriptor().bytes_per_segment as u64 + frames
    }
}

/// What a run may use.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Limits {
    /// Bytes of memory; `None` for what the machine has available now.
    pub max_memory: Option<u64>,
    /// Whether a finite run past [`LONG_SECONDS`] may start.
    pub yes: bool,
}

impl Limits {
    /// The memory a run may use: the limit given, or what the machine has available (or no
    /// bound where that cannot be read).
    pub fn memory(&self) -> u64 {
        self.max_memory
            .or_else(available_memory)
            .unwrap_or(u64::MAX)
    }

    /// Whether `bytes` fit in the memory a run may use: under [`SURELY_AVAILABLE`] the
    /// machine is not asked.
    pub fn fits(&self, bytes: u64) -> bool {
        match self.max_memory {
            Some(limit) => bytes <= limit,
            None => bytes <= SURELY_AVAILABLE || bytes <= self.memory(),
        }
    }

    /// Whose limit [`memory`](Limits::memory) is, for messages.
    pub fn whose_memory(&self) -> &'static str {
        match self.max_memory {
            Some(_) => "--max-memory",
            None => "the machine's available memory; --max-memory to set another",
        }
    }
}

/// The memory this machine has available now (Linux: `MemAvailable` of /proc/meminfo).
pub fn available_memory() -> Option<u64> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// A memory size as people write it, in the spelling Rerun's `MemoryLimit::parse` reads:
/// units in any case (`512mb`, `64KB`, `2 GiB`), decimal (kB, MB, GB, TB) or binary (KiB,
/// MiB, GiB, TiB); a share of the machine (`50%`) and bare bytes (`100B`) are left as they
/// are.
pub fn size_spelling(text: &str) -> String {
    let text = text.trim();
    let digits = text
        .find(|c: char| c.is_ascii_alphabetic())
        .unwrap_or(text.len());
    let (number, unit) = text.split_at(digits);
    let unit = match unit.to_ascii_lowercase().as_str() {
        "b" => "B",
        "kb" => "kB",
        "mb" => "MB",
        "gb" => "GB",
        "tb" => "TB",
        "kib" => "KiB",
        "mib" => "MiB",
        "gib" => "GiB",
        "tib" => "TiB",
        _ => return text.to_owned(),
    };
    format!("{}{unit}", number.trim())
}

/// A size for people: "512 MB", "3.2 GB".
pub fn bytes_text(bytes: u64) -> String {
    let b = bytes as f64;
    if b >= 1e12 {
        format!("{:.1} TB", b / 1e12)
    } else if b >= 1e9 {
        format!("{:.1} GB", b / 1e9)
    } else {
        format!("{:.0} MB", b / 1e6)
    }
}

/// A duration for people: "40 s", "3.5 min", "2.1 h", "12 days", "3e9 years".
pub fn seconds_text(seconds: f64) -> String {
    if !seconds.is_finite() {
        return "for ever".to_owned();
    }
    let s = Duration::from_secs_f64(seconds.clamp(0.0, 1e15)).as_secs_f64();
    if s < 120.0 {
        format!("{s:.0} s")
    } else if s < 7200.0 {
        format!("{:.1} min", s / 60.0)
    } else if s < 2.0 * 86_400.0 {
        format!("{:.1} h", s / 3600.0)
    } else if s < 2.0 * 365.25 * 86_400.0 {
        format!("{:.0} days", s / 86_400.0)
    } else {
        format!("{:.1e} years", seconds / (365.25 * 86_400.0))
    }
}

#[cfg(test)]
mod tests {
    use super::{Limits, SURELY_AVAILABLE, size_spelling};

    #[test]
    fn a_memory_limit_given_is_held_even_for_a_small_run() {
        let limits = Limits {
            max_memory: Some(1_000_000),
            yes: false,
        };
        assert!(limits.fits(1_000_000));
        assert!(!limits.fits(1_000_001));
        // Under the floor the machine is not asked, and the run fits.
        assert!(Limits::default().fits(SURELY_AVAILABLE));
        // Past it, the machine's available memory (or no bound where it cannot be read).
        assert_eq!(
            Limits::default().fits(SURELY_AVAILABLE + 1),
            SURELY_AVAILABLE < Limits::default().memory()
        );
    }

    #[test]
    fn sizes_are_read_in_any_case_and_shares_and_bytes_are_left_alone() {
        for (typed, read) in [
            ("512KB", "512kB"),
            ("512kb", "512kB"),
            ("64 mb", "64MB"),
            ("2gib", "2GiB"),
            ("1.5GB", "1.5GB"),
            ("100B", "100B"),
            ("50%", "50%"),
            ("lots", "lots"),
        ] {
            assert_eq!(size_spelling(typed), read, "{typed}");
            assert!(
                rerun::MemoryLimit::parse(&size_spelling(typed)).is_ok() || typed == "lots",
                "{typed}"
            );
        }
    }
}
