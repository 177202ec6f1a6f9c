//! What a soak run counts, and its report.

use std::collections::BTreeMap;
use std::fmt;
use std::time::Duration;

use drivebus::BusError;

use crate::fault::{Fault, FaultCounts};

/// The counts of one transport's run.
#[derive(Debug, Default)]
pub struct Tally {
    /// Transactions attempted.
    pub transactions: u64,
    /// Transactions that delivered their value or completed their write.
    pub succeeded: u64,
    /// Values delivered that the simulator did not hold (must stay 0).
    pub wrong_values: u64,
    /// Writes reported done whose value the simulator does not hold (must stay 0).
    pub lost_writes: u64,
    /// Writes reported done that an earlier failed write, executed late, overwrote: a failed
    /// write's outcome is unknown, and a link that holds requests back may execute it later.
    pub late_failed_writes: u64,
    /// Writes confirmed before the simulator executed them, and executed right after: the
    /// stale acknowledgement of a duplicated request taken for the next one's.
    pub early_confirmations: u64,
    /// Extra copies of non-idempotent write requests the client sent (must stay 0).
    pub write_retries: u64,
    /// Failed transactions by error kind.
    pub errors: BTreeMap<String, u64>,
    /// Resident memory before and after, KiB.
    pub rss_kib: (Option<u64>, Option<u64>),
    /// Wall time of the run.
    pub elapsed: Duration,
    /// CPU time of the whole process (client, proxy and simulator threads) during the run.
    pub cpu: Duration,
}

/// The report's name for an error's kind.
pub fn kind(error: &BusError) -> String {
    match error {
        BusError::Timeout => "timeout".into(),
        BusError::Frame(why) => format!("frame: {why}"),
        BusError::Io(kind) => format!("io: {kind:?}"),
        BusError::ModbusException { code, .. } => format!("modbus exception {code}"),
        BusError::SdoAbort { code, .. } => format!("sdo abort (server) {code:?}"),
        BusError::SdoClientAbort { code, .. } => format!("sdo abort (client) {code:?}"),
        other => format!("{other:?}"),
    }
}

impl Tally {
    /// Counts a failed transaction.
    pub fn failed(&mut self, error: &BusError) {
        *self.errors.entry(kind(error)).or_default() += 1;
    }

    /// Whether the run upheld its promises: no wrong value, no lost write, no repeated write.
    pub fn clean(&self) -> bool {
        self.wrong_values == 0 && self.lost_writes == 0 && self.write_retries == 0
    }

    /// Completed transactions per second.
    pub fn throughput(&self) -> f64 {
        self.transactions as f64 / self.elapsed.as_secs_f64().max(1e-9)
    }

    /// CPU microseconds per transaction.
    pub fn cpu_per_transaction_us(&self) -> f64 {
        self.cpu.as_secs_f64() * 1e6 / self.transactions.max(1) as f64
    }
}

/// One transport's report: its counts and the faults its proxy injected.
pub struct Report<'a> {
    /// The transport's name.
    pub transport: &'a str,
    /// Its counts.
    pub tally: &'a Tally,
    /// The faults injected.
    pub faults: &'a FaultCounts,
}

fn kib(value: Option<u64>) -> String {
    value.map_or("n/a".into(), |v| format!("{v} KiB"))
}

impl fmt::Display for Report<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let t = self.tally;
        writeln!(f, "== {} ==", self.transport)?;
        writeln!(f, "transactions          {}", t.transactions)?;
        writeln!(f, "succeeded             {}", t.succeeded)?;
        writeln!(f, "wrong values          {}", t.wrong_values)?;
        writeln!(f, "lost writes           {}", t.lost_writes)?;
        writeln!(f, "write retries         {}", t.write_retries)?;
        writeln!(f, "late failed writes    {}", t.late_failed_writes)?;
        writeln!(f, "early confirmations   {}", t.early_confirmations)?;
        let injected: Vec<String> = Fault::ALL
            .iter()
            .map(|&fault| format!("{} {}", fault.name(), self.faults.get(fault)))
            .collect();
        writeln!(
            f,
            "faults injected       {} ({})",
            self.faults.total(),
            injected.join(", ")
        )?;
        let failed: u64 = t.errors.values().sum();
        writeln!(f, "typed errors          {failed}")?;
        for (kind, count) in &t.errors {
            writeln!(f, "  {count:>8}  {kind}")?;
        }
        writeln!(
            f,
            "resident memory       {} -> {}",
            kib(t.rss_kib.0),
            kib(t.rss_kib.1)
        )?;
        writeln!(f, "elapsed               {:.2} s", t.elapsed.as_secs_f64())?;
        writeln!(
            f,
            "throughput            {:.0} transactions/s",
            t.throughput()
        )?;
        writeln!(
            f,
            "cpu per transaction   {:.1} us",
            t.cpu_per_transaction_us()
        )
    }
}
