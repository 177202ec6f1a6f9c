//! What the async benchmarks read of their own process and the machine: CPU time
//! (`getrusage`), resident memory (`/proc/self/statm`), the load average; and the simulated
//! drives' process (`mbap-sim`).

use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::Duration;

/// User + system CPU time of this whole process (every thread) so far.
pub fn process_cpu() -> Duration {
    // SAFETY: an all-zero `rusage` is a valid value; getrusage only writes the struct it is given.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: as above.
    unsafe { libc::getrusage(libc::RUSAGE_SELF, &mut usage) };
    let time = |t: libc::timeval| Duration::new(t.tv_sec as u64, t.tv_usec as u32 * 1000);
    time(usage.ru_utime) + time(usage.ru_stime)
}

/// Resident memory of this process in bytes (0 where `/proc` is missing).
pub fn resident_bytes() -> u64 {
    let statm = std::fs::read_to_string("/proc/self/statm").unwrap_or_default();
    let pages: u64 = statm
        .split_whitespace()
        .nth(1)
        .and_then(|p| p.parse().ok())
        .unwrap_or(0);
    // SAFETY: sysconf only reads a configuration value.
    let page = unsafe { libc::sysconf(libc::_SC_PAGESIZE) };
    pages * u64::try_from(page).unwrap_or(4096)
}

/// The 1-, 5- and 15-minute load averages, as `/proc/loadavg` writes them.
pub fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_default()
}

/// The simulated drives' process; it ends when this value is dropped.
pub struct Simulator {
    child: Child,
    /// One address per drive.
    pub addrs: Vec<String>,
}

impl Simulator {
    /// Starts `exe` (the `mbap-sim` binary) serving `drives` drives.
    pub fn start(exe: &Path, drives: usize) -> std::io::Result<Self> {
        let mut child = Command::new(exe)
            .arg(drives.to_string())
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()?;
        let mut line = String::new();
        if let Some(out) = child.stdout.take() {
            BufReader::new(out).read_line(&mut line)?;
        }
        let addrs: Vec<String> = line
            .split_whitespace()
            .map(|port| format!("127.0.0.1:{port}"))
            .collect();
        if addrs.len() != drives {
            let _ = child.kill();
            return Err(std::io::Error::other("mbap-sim did not print its ports"));
        }
        Ok(Self { child, addrs })
    }
}

impl Drop for Simulator {
    fn drop(&mut self) {
        drop(self.child.stdin.take());
        let _ = self.child.wait();
    }
}
