//! The faults the proxy injects, which of them a transport's line can produce, and their tally.

use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Duration;

use crate::proxy::Direction;
use crate::rng::Rng;

/// What happens to one frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Fault {
    /// Some bits of the frame change (where the protocol can detect it, see [`crate::proxy::Protocol`]).
    Corrupt,
    /// Only a prefix of the frame arrives (on TCP, the connection ends after it).
    Truncate,
    /// The frame arrives twice.
    Duplicate,
    /// The frame arrives late.
    Delay,
    /// The frame never arrives.
    Drop,
    /// The frame arrives after the next frame in the same direction.
    Reorder,
}

impl Fault {
    /// Every fault, in report order.
    pub const ALL: [Fault; 6] = [
        Fault::Corrupt,
        Fault::Truncate,
        Fault::Duplicate,
        Fault::Delay,
        Fault::Drop,
        Fault::Reorder,
    ];

    /// The report's name for it.
    pub fn name(self) -> &'static str {
        match self {
            Fault::Corrupt => "corrupt",
            Fault::Truncate => "truncate",
            Fault::Duplicate => "duplicate",
            Fault::Delay => "delay",
            Fault::Drop => "drop",
            Fault::Reorder => "reorder",
        }
    }

    fn slot(self) -> usize {
        Fault::ALL.iter().position(|&f| f == self).unwrap_or(0)
    }
}

/// How a transport's proxy misbehaves.
#[derive(Debug, Clone, Copy)]
pub struct FaultPlan {
    /// Share of frames that get a fault (0.01: 1 %).
    pub rate: f64,
    /// The faults this line can produce on requests, picked with equal odds.
    pub request_kinds: &'static [Fault],
    /// The faults this line can produce on answers, picked with equal odds.
    pub response_kinds: &'static [Fault],
    /// Longest [`Fault::Delay`].
    pub max_delay: Duration,
}

/// How many faults of each kind were injected, over all directions of a transport.
#[derive(Debug, Default)]
pub struct FaultCounts([AtomicU64; 6]);

impl FaultCounts {
    fn add(&self, fault: Fault) {
        self.0[fault.slot()].fetch_add(1, Ordering::Relaxed);
    }

    /// The count of `fault`.
    pub fn get(&self, fault: Fault) -> u64 {
        self.0[fault.slot()].load(Ordering::Relaxed)
    }

    /// All faults injected.
    pub fn total(&self) -> u64 {
        Fault::ALL.iter().map(|&fault| self.get(fault)).sum()
    }
}

/// Decides each frame's fate from a seeded stream, and counts what it decided.
#[derive(Debug)]
pub struct Injector<'a> {
    /// The stream faults and their details (positions, masks, delays) are drawn from.
    pub rng: Rng,
    plan: FaultPlan,
    kinds: &'static [Fault],
    counts: &'a FaultCounts,
}

impl<'a> Injector<'a> {
    /// An injector for frames travelling in `direction`, following `plan`, drawing from `rng`,
    /// tallying into `counts`.
    pub fn new(rng: Rng, plan: FaultPlan, direction: Direction, counts: &'a FaultCounts) -> Self {
        let kinds = match direction {
            Direction::Request => plan.request_kinds,
            Direction::Response => plan.response_kinds,
        };
        Self {
            rng,
            plan,
            kinds,
            counts,
        }
    }

    /// The fault for the next frame, if any.
    pub fn next_fault(&mut self) -> Option<Fault> {
        if self.kinds.is_empty() || !self.rng.chance(self.plan.rate) {
            return None;
        }
        let fault = self.kinds[self.rng.below(self.kinds.len() as u64) as usize];
        self.counts.add(fault);
        Some(fault)
    }

    /// How long a [`Fault::Delay`] holds the frame back.
    pub fn delay(&mut self) -> Duration {
        let max = self.plan.max_delay.as_micros().max(1) as u64;
        Duration::from_micros(1 + self.rng.below(max))
    }
}
