//! The limits a run or a study must keep: `--max-cpu` and `--max-memory`, shared by both
//! commands.

use crate::run::cost::{self, Limits};

/// The limits a run or a study must keep, shared by both commands.
#[derive(Debug, clap::Args)]
pub struct LimitArgs {
    /// Memory it may use, e.g. 4GB or 50% [default: what the machine has available]. A run
    /// or study predicted to need more is refused before it starts.
    #[arg(long, value_name = "SIZE", value_parser = parse_memory_size)]
    pub max_memory: Option<MemorySize>,

    /// Start it even if it is predicted to take more than a day of CPU (a finite run).
    #[arg(long)]
    pub yes: bool,
}

impl LimitArgs {
    /// The limits the flags set.
    pub fn limits(&self) -> Limits {
        Limits {
            max_memory: self.max_memory.map(|m| m.bytes),
            yes: self.yes,
        }
    }
}

/// `--max-memory SIZE`: a size in bytes, as the user wrote it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MemorySize {
    pub bytes: u64,
}

/// `--max-memory SIZE`: 512MB, 8GB, or a share of the machine's memory (50%).
fn parse_memory_size(text: &str) -> Result<MemorySize, String> {
    match rerun::MemoryLimit::parse(&cost::size_spelling(text)) {
        Ok(limit) if !limit.is_unlimited() && limit.as_bytes() > 0 => Ok(MemorySize {
            bytes: limit.as_bytes(),
        }),
        Ok(_) => Err(format!(
            "{text}: give a size above zero, e.g. 512MB, 8GB or 50%"
        )),
        Err(err) => Err(format!("{err}; give e.g. 512MB, 8GB or 50%")),
    }
}
