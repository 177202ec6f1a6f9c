//! Ctrl-C and SIGTERM end a watch between samples instead of killing the process, so what the
//! watch changed on the drive (`--pdo`) is restored and the output ends with a whole line.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use crate::error::CliError;

/// Longest nap between looks at the flag: how late a Ctrl-C is noticed at most.
const NAP: Duration = Duration::from_millis(20);

/// Set once the process was asked to stop.
#[derive(Clone)]
pub struct Interrupt(Arc<AtomicBool>);

impl Interrupt {
    /// Catches SIGINT and SIGTERM from now on. A second one ends the process at once (exit
    /// code 1), for a drive that does not answer while its configuration is restored.
    pub fn catch() -> Result<Self, CliError> {
        let flag = Arc::new(AtomicBool::new(false));
        for signal in [signal_hook::consts::SIGINT, signal_hook::consts::SIGTERM] {
            let caught =
                |e: std::io::Error| CliError::Io(format!("cannot catch signal {signal}: {e}"));
            // The shutdown first: it looks at the flag before the second handler sets it.
            signal_hook::flag::register_conditional_shutdown(signal, 1, Arc::clone(&flag))
                .map_err(caught)?;
            signal_hook::flag::register(signal, Arc::clone(&flag)).map_err(caught)?;
        }
        Ok(Self(flag))
    }

    /// Whether the process was asked to stop.
    pub fn raised(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }

    /// Sleeps until `deadline`; `false` when interrupted first.
    pub fn sleep_until(&self, deadline: Instant) -> bool {
        loop {
            if self.raised() {
                return false;
            }
            let now = Instant::now();
            if now >= deadline {
                return true;
            }
            std::thread::sleep((deadline - now).min(NAP));
        }
    }
}
