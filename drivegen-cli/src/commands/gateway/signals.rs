//! SIGINT and SIGTERM for the gateway, caught from before any bus opens until the process ends.
//! The first starts the clean stop. A later one, while the pollers put back what they changed
//! on the drives (the TPDO configuration of `pdo` drives, their NMT state), is logged and does
//! not cut that short: a drive left mapped for the gateway would keep sending its TPDO to
//! nobody, with its own configuration lost. The restore is bounded by the bus timeouts (a
//! drive that does not answer costs its `timeout_ms` per write); SIGKILL still ends the process
//! at once, as a service manager does after its grace period.

use tokio::signal::unix::{signal, Signal, SignalKind};
use tokio::sync::mpsc;

use crate::error::CliError;

/// The two signals that stop the gateway.
pub struct Signals {
    interrupt: Signal,
    terminate: Signal,
}

impl Signals {
    /// Catches SIGINT and SIGTERM from now on (inside the gateway's runtime): neither ends the
    /// process any more, the gateway stops by itself.
    pub fn catch() -> Result<Self, CliError> {
        let caught =
            |name: &str, e: std::io::Error| CliError::Io(format!("cannot watch for {name}: {e}"));
        Ok(Self {
            interrupt: signal(SignalKind::interrupt()).map_err(|e| caught("SIGINT", e))?,
            terminate: signal(SignalKind::terminate()).map_err(|e| caught("SIGTERM", e))?,
        })
    }

    /// Waits for the next SIGINT or SIGTERM; its name.
    pub async fn next(&mut self) -> &'static str {
        tokio::select! {
            _ = self.interrupt.recv() => "SIGINT",
            _ = self.terminate.recv() => "SIGTERM",
        }
    }

    /// After the first signal: waits until every poller ended (each holds a sender of `done`,
    /// dropped once its drives are put back), logging each further signal.
    pub async fn until_stopped(&mut self, mut done: mpsc::Receiver<()>) {
        loop {
            tokio::select! {
                // A signal that came is logged even when the pollers are done by then.
                biased;
                name = self.next() => tracing::warn!(
                    "{name} while stopping: the drives are being put back as they were \
                     (TPDO configuration, NMT state); the gateway ends once that is done \
                     (SIGKILL ends it at once)"
                ),
                // Every sender dropped: each poller has put its drives back.
                None = done.recv() => return,
            }
        }
    }
}
