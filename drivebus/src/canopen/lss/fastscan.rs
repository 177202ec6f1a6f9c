//! Fastscan (CiA 305, command specifier 51h), sans-I/O: the LSS address of one non-configured
//! node, found bit by bit, which the node then holds in LSS configuration state.
//!
//! A first step (BitChecked 80h) resets every non-configured slave's scan and asks whether there
//! is any. Then for each of the four words (LSSSub 0-3), bit 31 down to bit 0: "does a slave
//! whose word matches the bits found so far have a 0 here?" Answered: the bit is 0; silence: it
//! is 1. A last step per word (BitChecked 0, LSSNext the next word) confirms the whole word and
//! moves the matching slaves on; after the serial number the one node left enters configuration
//! state. That is 1 + 4 × 33 steps, each as long as the timeout (the first may wait longer,
//! [`Fastscan::with_reset_wait`]), because silence is an answer:
//! choose the timeout from how fast the slaves answer, not from how long a user waits.
//!
//! Slaves with smaller addresses win each step, so repeated scans find the nodes in ascending
//! LSS address order; give each its node id before the next scan (a configured node no longer
//! takes part).

use core::time::Duration;

use super::{Command, LssAddress, LssError, Response};
use crate::canopen::frame::CanFrame;

/// BitChecked of the first step: resets the slaves' scan (CiA 305).
const RESET: u8 = 0x80;

/// Where a Fastscan stands.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum FastscanProgress {
    /// Not finished.
    Pending,
    /// A node with this LSS address is now in LSS configuration state.
    Found(LssAddress),
    /// No non-configured node answered.
    NoneLeft,
    /// The scan lost its node.
    Failed(LssError),
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Step {
    Reset,
    Bit(u8),
    Confirm,
}

/// A Fastscan run: see the module documentation.
#[derive(Debug, Clone)]
pub struct Fastscan {
    words: [u32; 4],
    sub: u8,
    step: Step,
    timeout: Duration,
    reset_wait: Duration,
    deadline: Duration,
    outbox: Option<CanFrame>,
    answered: bool,
    end: Option<FastscanProgress>,
}

impl Fastscan {
    /// Starts a scan at `now`; each step waits `timeout` for answers.
    pub fn new(timeout: Duration, now: Duration) -> Self {
        let mut scan = Self {
            words: [0; 4],
            sub: 0,
            step: Step::Reset,
            timeout,
            reset_wait: timeout,
            deadline: now,
            outbox: None,
            answered: false,
            end: None,
        };
        scan.queue(now);
        scan
    }

    /// Lets the first step (does any non-configured node answer?) wait `wait` instead of one
    /// step: a node that just took another node id, or one still starting, answers in time,
    /// and answers to earlier commands are over before the bits are asked. Call before sending.
    pub fn with_reset_wait(mut self, wait: Duration, now: Duration) -> Self {
        self.reset_wait = wait;
        if self.step == Step::Reset {
            self.deadline = now + wait;
        }
        self
    }

    /// The next frame to send.
    pub fn poll_transmit(&mut self) -> Option<CanFrame> {
        self.outbox.take()
    }

    /// When the current step ends; `None` once the scan finished.
    pub fn deadline(&self) -> Option<Duration> {
        self.end.is_none().then_some(self.deadline)
    }

    /// Where the scan stands.
    pub fn progress(&self) -> FastscanProgress {
        self.end.clone().unwrap_or(FastscanProgress::Pending)
    }

    /// How many steps are done (of 133), for progress reports.
    pub fn steps_done(&self) -> u32 {
        let within = match self.step {
            Step::Reset => return 0,
            Step::Bit(bit) => 31 - u32::from(bit),
            Step::Confirm => 32,
        };
        1 + u32::from(self.sub) * 33 + within
    }

    /// Feeds a received frame; an "identify slave" answer (4Fh) marks the step answered.
    pub fn handle(&mut self, frame: &CanFrame, _now: Duration) -> FastscanProgress {
        if self.end.is_none() && Response::decode(frame) == Some(Response::IdentifySlave) {
            self.answered = true;
        }
        self.progress()
    }

    /// Ends the current step if its deadline passed at `now`, and queues the next one.
    pub fn handle_timeout(&mut self, now: Duration) -> FastscanProgress {
        if self.end.is_some() || now < self.deadline {
            return self.progress();
        }
        let answered = core::mem::take(&mut self.answered);
        let word = &mut self.words[usize::from(self.sub)];
        self.step = match self.step {
            Step::Reset if !answered => return self.finish(FastscanProgress::NoneLeft),
            Step::Reset => Step::Bit(31),
            Step::Bit(bit) => {
                if !answered {
                    *word |= 1 << bit;
                }
                bit.checked_sub(1).map_or(Step::Confirm, Step::Bit)
            }
            Step::Confirm if !answered => {
                return self.finish(FastscanProgress::Failed(LssError::FastscanLost))
            }
            Step::Confirm if self.sub == 3 => {
                let found = LssAddress::from_words(self.words);
                return self.finish(FastscanProgress::Found(found));
            }
            Step::Confirm => {
                self.sub += 1;
                Step::Bit(31)
            }
        };
        self.queue(now);
        FastscanProgress::Pending
    }

    /// Queues the current step's frame and starts its timer.
    fn queue(&mut self, now: Duration) {
        let sub = self.sub;
        let id = self.words[usize::from(sub)];
        let command = match self.step {
            Step::Reset => Command::Fastscan {
                id: 0,
                bit: RESET,
                sub: 0,
                next: 0,
            },
            Step::Bit(bit) => Command::Fastscan {
                id,
                bit,
                sub,
                next: sub,
            },
            Step::Confirm => Command::Fastscan {
                id,
                bit: 0,
                sub,
                next: (sub + 1) % 4,
            },
        };
        self.outbox = Some(command.encode());
        let wait = if self.step == Step::Reset {
            self.reset_wait
        } else {
            self.timeout
        };
        self.deadline = now + wait;
    }

    fn finish(&mut self, end: FastscanProgress) -> FastscanProgress {
        self.outbox = None;
        self.end = Some(end.clone());
        end
    }
}
