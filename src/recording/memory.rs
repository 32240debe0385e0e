//! A destination in memory for a caller in the same process (a test): the messages of a
//! recording, kept for it to read back (`OutputArgs::memory`).

/// The messages of a recording kept in memory (`OutputArgs::memory`), shared with whoever
/// reads them.
#[derive(Clone, Default)]
pub struct InMemory(std::sync::Arc<std::sync::Mutex<Vec<rerun::log::LogMsg>>>);

impl InMemory {
    /// The messages received so far.
    pub fn messages(&self) -> Vec<rerun::log::LogMsg> {
        self.0
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
            .clone()
    }

    /// A sink that appends to these messages.
    pub(super) fn sink(&self) -> rerun::sink::CallbackSink {
        let kept = std::sync::Arc::clone(&self.0);
        rerun::sink::CallbackSink::new(move |msgs| {
            kept.lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner)
                .extend_from_slice(msgs);
        })
    }
}

impl std::fmt::Debug for InMemory {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "InMemory({} messages)", self.messages().len())
    }
}
