//! The soak's workload: random reads and non-idempotent writes, each checked against the
//! simulator.

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use crate::endpoint::{Endpoint, REGISTERS};
use crate::resources::{cpu_time, resident_kib};
use crate::rng::Rng;
use crate::tally::Tally;
use crate::truth::Truth;

/// How often a long run says how far it is (on stderr).
const PROGRESS_EVERY: u64 = 100_000;

/// Runs `transactions` transactions on `endpoint`, half reads and half writes, from `rng`;
/// stops early once `deadline` (if any) has passed.
pub fn soak(
    endpoint: &mut dyn Endpoint,
    truth: &Truth,
    transactions: u64,
    deadline: Option<Instant>,
    rng: &mut Rng,
) -> Tally {
    let mut tally = Tally {
        rss_kib: (resident_kib(), None),
        ..Tally::default()
    };
    let (started, cpu) = (Instant::now(), cpu_time());
    let mut failed_writes = FailedWrites::default();
    for done in 0..transactions {
        if done % 1000 == 0 && deadline.is_some_and(|deadline| Instant::now() >= deadline) {
            break;
        }
        if done > 0 && done % PROGRESS_EVERY == 0 {
            eprintln!(
                "soak: {done} transactions after {:.0} s, {} wrong values",
                started.elapsed().as_secs_f64(),
                tally.wrong_values
            );
        }
        let first = rng.below(REGISTERS as u64) as usize;
        let span = 1 + rng.below(endpoint.max_span().min(REGISTERS - first) as u64) as usize;
        if rng.chance(0.5) {
            read(endpoint, truth, first, span, &mut tally);
        } else {
            let values: Vec<u16> = (0..span).map(|_| rng.u16()).collect();
            write(
                endpoint,
                truth,
                first,
                &values,
                &mut failed_writes,
                &mut tally,
            );
        }
        tally.transactions += 1;
    }
    tally.elapsed = started.elapsed();
    tally.cpu = cpu_time().saturating_sub(cpu);
    tally.rss_kib.1 = resident_kib();
    tally
}

/// One read; each value must be one the simulator held while the read was under way (a
/// request the proxy held back may still change it).
fn read(endpoint: &mut dyn Endpoint, truth: &Truth, first: usize, span: usize, tally: &mut Tally) {
    let mut out = [0u16; REGISTERS];
    let before = truth.snapshot();
    let result = endpoint.read(first, &mut out[..span]);
    let after = truth.snapshot();
    match result {
        Ok(()) => {
            tally.succeeded += 1;
            let wrong = (first..first + span)
                .zip(&out[..span])
                .filter(|&(slot, value)| *value != before[slot] && *value != after[slot])
                .count();
            if wrong > 0 {
                eprintln!(
                    "wrong value: read {first}+{span} gave {:?}, simulator held {:?} then {:?}",
                    &out[..span],
                    &before[first..first + span],
                    &after[first..first + span]
                );
            }
            tally.wrong_values += wrong as u64;
        }
        Err(error) => tally.failed(&error),
    }
}

/// The last writes that failed: their outcome is unknown, and a request a proxy held back may
/// still be executed after later writes.
#[derive(Debug, Default)]
struct FailedWrites(VecDeque<(usize, Vec<u16>)>);

impl FailedWrites {
    /// How many are remembered.
    const KEPT: usize = 16;

    fn add(&mut self, first: usize, values: &[u16]) {
        if self.0.len() == Self::KEPT {
            self.0.pop_front();
        }
        self.0.push_back((first, values.to_vec()));
    }

    /// Whether `value` at `slot` is what one of them wrote there.
    fn wrote(&self, slot: usize, value: u16) -> bool {
        self.0.iter().any(|(first, values)| {
            slot.checked_sub(*first)
                .and_then(|at| values.get(at))
                .is_some_and(|&written| written == value)
        })
    }
}

/// One non-idempotent write: sent once, and held by the simulator when reported done (unless
/// an earlier failed write was executed after it).
fn write(
    endpoint: &mut dyn Endpoint,
    truth: &Truth,
    first: usize,
    values: &[u16],
    failed_writes: &mut FailedWrites,
    tally: &mut Tally,
) {
    let sent_before = endpoint.write_requests_sent();
    let result = endpoint.write(first, values);
    let sent = endpoint.write_requests_sent() - sent_before;
    // The SDO endpoint writes register by register: one request each.
    let expected = if endpoint.max_span() == 1 {
        values.len() as u64
    } else {
        1
    };
    tally.write_retries += sent.saturating_sub(expected);
    match result {
        Ok(()) => {
            tally.succeeded += 1;
            let held = truth.snapshot();
            let differs: Vec<usize> = (first..first + values.len())
                .filter(|&slot| held[slot] != values[slot - first])
                .collect();
            if differs.is_empty() {
                return;
            }
            if differs
                .iter()
                .all(|&slot| failed_writes.wrote(slot, held[slot]))
            {
                tally.late_failed_writes += 1;
            } else if held_soon(truth, first, values) {
                tally.early_confirmations += 1;
            } else {
                eprintln!(
                    "lost write: wrote {values:?} at {first}, simulator holds {:?}",
                    &held[first..first + values.len()]
                );
                tally.lost_writes += 1;
            }
        }
        Err(error) => {
            failed_writes.add(first, values);
            tally.failed(&error);
        }
    }
}

/// How long a write confirmed early has to be executed: longer than any delay the proxy
/// injects (twice the 100 ms timeout) plus scheduling on a busy machine.
const SOON: Duration = Duration::from_millis(300);

/// Whether the simulator holds `values` from `first` within [`SOON`]: a write confirmed before
/// it was executed (SDO answers carry no transaction id: the second acknowledgement of a
/// duplicated download request confirms the next download of the same object).
fn held_soon(truth: &Truth, first: usize, values: &[u16]) -> bool {
    let deadline = Instant::now() + SOON;
    while Instant::now() < deadline {
        std::thread::sleep(Duration::from_millis(5));
        if truth.snapshot()[first..first + values.len()] == *values {
            return true;
        }
    }
    false
}
