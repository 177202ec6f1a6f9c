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

/// User + system CPU time of another process so far (`/proc/PID/stat`; zero where it is missing).
pub fn other_process_cpu(pid: u32) -> Duration {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).unwrap_or_default();
    // The fields after the command name (which may hold spaces) end with `)`.
    let after = stat.rsplit_once(')').map_or("", |(_, rest)| rest);
    let field = |n: usize| -> u64 {
        after
            .split_whitespace()
            .nth(n)
            .and_then(|v| v.parse().ok())
            .unwrap_or(0)
    };
    // utime and stime are fields 14 and 15 of the whole line, 11 and 12 after the name.
    let ticks = field(11) + field(12);
    // SAFETY: sysconf only reads a configuration value.
    let per_second = unsafe { libc::sysconf(libc::_SC_CLK_TCK) }.max(1) as u64;
    Duration::from_nanos(ticks * 1_000_000_000 / per_second)
}

/// Resident memory of another process in bytes (`VmRSS` of `/proc/PID/status`; 0 if missing).
pub fn other_resident_bytes(pid: u32) -> u64 {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmRSS:"))
        .and_then(|v| v.split_whitespace().next()?.parse::<u64>().ok())
        .map_or(0, |kib| kib * 1024)
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
