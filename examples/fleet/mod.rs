//! The fleet's four drives, one module each: the simulated drive started on its protocol, then
//! the task that enables it, gives it a speed, publishes its live values and stops it.

use std::error::Error;
use std::sync::{Arc, Mutex};
use std::time::Duration;

use tokio::sync::watch;

pub mod kinco;
pub mod lafert;
pub mod lenze;
pub mod swd;

/// The drives, in column order.
pub const NAMES: [&str; 4] = ["lafert-smartris", "lenze-smd", "ezwheel-swd", "kinco-fd"];

/// Each drive's latest values, as printed, in column order.
pub type Live = Arc<Mutex<[String; 4]>>;

/// What a drive task ends with: its last values after the stop, or why it failed.
pub type Outcome = Result<String, Box<dyn Error + Send + Sync>>;

/// How often a task reads its drive.
const POLL: Duration = Duration::from_millis(100);

/// Publishes `text` as the drive's column.
pub fn publish(live: &Live, column: usize, text: String) {
    // A poisoned lock only means another task panicked; its values are still printable.
    let mut columns = live.lock().unwrap_or_else(|e| e.into_inner());
    columns[column] = text;
}

/// True once the main task asked the drives to stop.
pub fn stop_asked(stopping: &watch::Receiver<bool>) -> bool {
    *stopping.borrow()
}

/// Waits for the next poll, or less if the stop is asked meanwhile.
pub async fn pause(stopping: &mut watch::Receiver<bool>) {
    // A closed channel (the main task gone) ends the wait as a stop would.
    let _ = tokio::time::timeout(POLL, stopping.changed()).await;
}

/// The description of a drive family in the workspace.
pub fn description(family: &str) -> String {
    format!("{}/../descriptions/{family}", env!("CARGO_MANIFEST_DIR"))
}
