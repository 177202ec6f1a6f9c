//! One LSS exchange, sans-I/O: the command frames (a selective switch is four, an identify
//! remote slave range six) and the answers to the last one, driven by the caller's clock.
//!
//! A command only one slave may answer (selective switch, configure, store, inquire) waits a
//! short settle time after the first answer: a second answer in that time is
//! [`LssError::SeveralAnswers`], never silently the wrong node's value. A command any number
//! of slaves answer (identify remote slave, identify non-configured slave) counts the answers
//! until the timeout.

use core::time::Duration;

use super::{Command, LssError, Response};
use crate::canopen::frame::CanFrame;

/// Most commands one exchange sends (an identify remote slave range).
pub const MAX_COMMANDS: usize = 6;

/// How many slaves may answer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Answers {
    /// Exactly one; a second is an error.
    One,
    /// Any number; they are counted until the timeout.
    Any,
}

/// What an exchange ended with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Outcome {
    /// The (first) answer; `None` for commands nobody answers, or if none came ([`Answers::Any`]).
    pub response: Option<Response>,
    /// How many slaves answered.
    pub count: usize,
}

/// The state of an exchange after a frame, the time or a transmission.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Progress {
    /// Not finished: send what [`Exchange::poll_transmit`] gives, feed frames and the time.
    Pending,
    /// Finished.
    Done(Outcome),
    /// Failed.
    Failed(LssError),
}

/// One exchange: see the module documentation.
#[derive(Debug, Clone)]
pub struct Exchange {
    commands: [Option<Command>; MAX_COMMANDS],
    sent: usize,
    last: Option<Command>,
    answers: Answers,
    settle: Duration,
    deadline: Duration,
    first: Option<Response>,
    count: usize,
    end: Option<Progress>,
}

impl Exchange {
    /// Sends `commands` (at most [`MAX_COMMANDS`]; more fail with [`LssError::Bus`]) and waits up to
    /// `timeout` from `now` for the answers to the last one. Only one slave may answer unless the
    /// last command is an identification (identify remote slave, non-configured, Fastscan).
    pub fn new(commands: &[Command], timeout: Duration, now: Duration) -> Self {
        let mut queued = [None; MAX_COMMANDS];
        let too_many = commands.len() > MAX_COMMANDS;
        for (slot, command) in queued.iter_mut().zip(commands) {
            *slot = Some(*command);
        }
        let last = commands.last().copied();
        let answers = match last {
            Some(
                Command::IdentifyRemote(..)
                | Command::IdentifyNonConfigured
                | Command::Fastscan { .. },
            ) => Answers::Any,
            _ => Answers::One,
        };
        Self {
            commands: queued,
            sent: 0,
            last,
            answers,
            settle: timeout / 5,
            deadline: now + timeout,
            first: None,
            count: 0,
            end: too_many.then_some(Progress::Failed(LssError::Bus(
                crate::error::BusError::Frame("more LSS commands than one exchange sends"),
            ))),
        }
    }

    /// One command.
    pub fn single(command: Command, timeout: Duration, now: Duration) -> Self {
        Self::new(&[command], timeout, now)
    }

    /// Sets how long a command only one slave may answer waits for a second answer after the
    /// first (default: a fifth of the timeout).
    pub fn with_settle(mut self, settle: Duration) -> Self {
        self.settle = settle;
        self
    }

    /// How many slaves may answer.
    pub fn answers(&self) -> Answers {
        self.answers
    }

    /// The next frame to send.
    pub fn poll_transmit(&mut self) -> Option<CanFrame> {
        if self.end.is_some() {
            return None;
        }
        let command = self.commands.get_mut(self.sent)?.take()?;
        self.sent += 1;
        Some(command.encode())
    }

    /// Where the exchange stands. A command nobody answers is done once sent.
    pub fn progress(&self) -> Progress {
        if let Some(end) = &self.end {
            return end.clone();
        }
        let all_sent = self.commands.iter().all(Option::is_none);
        match self.last {
            Some(last) if last.expects_answer() || !all_sent => Progress::Pending,
            _ => Progress::Done(Outcome {
                response: None,
                count: 0,
            }),
        }
    }

    /// When to call [`Exchange::handle_timeout`]; `None` once finished.
    pub fn deadline(&self) -> Option<Duration> {
        matches!(self.progress(), Progress::Pending).then_some(self.deadline)
    }

    /// Feeds a received frame (of any COB-ID; frames that do not answer the last command are
    /// ignored).
    pub fn handle(&mut self, frame: &CanFrame, now: Duration) -> Progress {
        let Some(response) = Response::decode(frame) else {
            return self.progress();
        };
        let answers_last = self.last.is_some_and(|last| last.is_answered_by(&response));
        if !answers_last || self.end.is_some() {
            return self.progress();
        }
        self.count += 1;
        match (self.answers, self.first) {
            (Answers::One, Some(_)) => self.finish(Progress::Failed(LssError::SeveralAnswers)),
            (Answers::One, None) => {
                self.first = Some(response);
                self.deadline = self.deadline.min(now + self.settle);
                self.progress()
            }
            (Answers::Any, _) => {
                self.first.get_or_insert(response);
                self.progress()
            }
        }
    }

    /// Ends the exchange if its deadline passed at `now`.
    pub fn handle_timeout(&mut self, now: Duration) -> Progress {
        if self.end.is_some() || now < self.deadline {
            return self.progress();
        }
        let end = match (self.answers, self.first) {
            (Answers::One, None) => Progress::Failed(LssError::NoAnswer),
            (_, response) => Progress::Done(Outcome {
                response,
                count: self.count,
            }),
        };
        self.finish(end)
    }

    fn finish(&mut self, end: Progress) -> Progress {
        self.end = Some(end.clone());
        end
    }
}
