//! The sans-I/O boot of one node: which request comes next, given how the last one went.

use super::{BootError, BootReport, BootStep, NodeBoot};
use crate::canopen::nmt::NmtCommand;
use crate::error::BusError;

/// What the driver does next for the node.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Action<'a> {
    /// Read `index:subindex` (a 4-byte value at most) and report it with
    /// [`BootProcedure::read`].
    Read {
        /// Object index.
        index: u16,
        /// Subindex.
        subindex: u8,
    },
    /// Write `data` to `index:subindex` and report it with [`BootProcedure::wrote`].
    Write {
        /// Object index.
        index: u16,
        /// Subindex.
        subindex: u8,
        /// The value's bytes.
        data: &'a [u8],
    },
    /// Send this NMT command to the node and report it with [`BootProcedure::sent`].
    Nmt(NmtCommand),
    /// Finished: the report is [`BootProcedure::report`].
    Finished,
}

/// The boot of one node as a sequence of requests.
#[derive(Debug, Clone)]
pub struct BootProcedure<'a> {
    plan: &'a NodeBoot,
    step: BootStep,
    device_type: Option<u32>,
    outcome: Option<Result<(), BootError>>,
    heartbeat_ms: [u8; 2],
}

impl<'a> BootProcedure<'a> {
    /// The boot `plan` describes, not started.
    pub fn new(plan: &'a NodeBoot) -> Self {
        let ms = plan
            .heartbeat
            .map_or(0, |p| u16::try_from(p.as_millis()).unwrap_or(u16::MAX));
        Self {
            plan,
            step: BootStep::Probe,
            device_type: None,
            outcome: None,
            heartbeat_ms: ms.to_le_bytes(),
        }
    }

    /// What to do now.
    pub fn action(&self) -> Action<'_> {
        if self.outcome.is_some() {
            return Action::Finished;
        }
        match self.step {
            BootStep::Probe => Action::Read {
                index: 0x1000,
                subindex: 0,
            },
            BootStep::Identity(subindex) => Action::Read {
                index: 0x1018,
                subindex,
            },
            BootStep::Heartbeat => Action::Write {
                index: 0x1017,
                subindex: 0,
                data: &self.heartbeat_ms,
            },
            BootStep::Write(n) => {
                let write = &self.plan.writes[n];
                Action::Write {
                    index: write.index,
                    subindex: write.subindex,
                    data: &write.data,
                }
            }
            BootStep::Start => Action::Nmt(NmtCommand::Start),
        }
    }

    /// The value of the last [`Action::Read`], or why it failed.
    pub fn read(&mut self, value: Result<u32, BusError>) {
        match (self.step, value) {
            (BootStep::Probe, Ok(device_type)) => {
                self.device_type = Some(device_type);
                self.advance();
            }
            (BootStep::Probe, Err(BusError::Timeout)) => self.finish(Err(BootError::Missing)),
            (BootStep::Identity(subindex), Ok(found)) => match self.plan.identity.entry(subindex) {
                Some(expected) if expected != found => self.finish(Err(BootError::Foreign {
                    subindex,
                    expected,
                    found,
                })),
                _ => self.advance(),
            },
            (step, Err(error)) => self.finish(Err(BootError::Step { step, error })),
            (_, Ok(_)) => self.advance(),
        }
    }

    /// How the last [`Action::Write`] went.
    pub fn wrote(&mut self, result: Result<(), BusError>) {
        match result {
            Ok(()) => self.advance(),
            Err(error) => self.finish(Err(BootError::Step {
                step: self.step,
                error,
            })),
        }
    }

    /// How sending the last [`Action::Nmt`] went.
    pub fn sent(&mut self, result: Result<(), BusError>) {
        self.wrote(result);
    }

    /// The report. Before [`Action::Finished`] it says the boot stopped at its current step
    /// (a driver that gives up early reports that).
    pub fn report(&self) -> BootReport {
        let unfinished = BootError::Step {
            step: self.step,
            error: BusError::Frame("the boot was not finished"),
        };
        BootReport {
            node: self.plan.node,
            device_type: self.device_type,
            result: self.outcome.clone().unwrap_or(Err(unfinished)),
        }
    }

    /// How long to wait for the node's heartbeat from now on: once it booted with a heartbeat.
    pub fn heartbeat_watch(&self) -> Option<core::time::Duration> {
        match self.outcome {
            Some(Ok(())) => self.plan.heartbeat.map(super::consumer_timeout),
            _ => None,
        }
    }

    fn finish(&mut self, outcome: Result<(), BootError>) {
        self.outcome = Some(outcome);
    }

    /// Moves to the next step the plan asks for; after the last one the boot is done.
    fn advance(&mut self) {
        let mut next = self.following(self.step);
        while let Some(step) = next.filter(|s| !self.wanted(*s)) {
            next = self.following(step);
        }
        match next {
            Some(step) => self.step = step,
            None => self.finish(Ok(())),
        }
    }

    /// The step after `step` in the full sequence.
    fn following(&self, step: BootStep) -> Option<BootStep> {
        Some(match step {
            BootStep::Probe => BootStep::Identity(1),
            BootStep::Identity(sub) if sub < 3 => BootStep::Identity(sub + 1),
            BootStep::Identity(_) => BootStep::Heartbeat,
            BootStep::Heartbeat => BootStep::Write(0),
            BootStep::Write(n) if n + 1 < self.plan.writes.len() => BootStep::Write(n + 1),
            BootStep::Write(_) => BootStep::Start,
            BootStep::Start => return None,
        })
    }

    fn wanted(&self, step: BootStep) -> bool {
        match step {
            BootStep::Probe => true,
            BootStep::Identity(sub) => self.plan.identity.entry(sub).is_some(),
            BootStep::Heartbeat => self.plan.heartbeat.is_some(),
            BootStep::Write(n) => n < self.plan.writes.len(),
            BootStep::Start => self.plan.start,
        }
    }
}

#[cfg(test)]
mod tests {
    use std::string::String;
    use std::vec;
    use std::vec::Vec;

    use super::super::{BootWrite, ExpectedIdentity};
    use super::*;
    use crate::canopen::address::NodeId;
    use crate::canopen::sdo::AbortCode;

    fn plan() -> NodeBoot {
        NodeBoot {
            node: NodeId(4),
            identity: ExpectedIdentity {
                vendor_id: Some(0x515),
                product_code: None,
                revision: Some(2),
            },
            heartbeat: Some(core::time::Duration::from_millis(100)),
            writes: vec![BootWrite {
                index: 0x2000,
                subindex: 0,
                data: vec![1, 2],
            }],
            start: true,
        }
    }

    /// Runs `procedure`, answering reads from `values` in order, and every write and NMT `Ok`;
    /// returns the actions taken.
    fn run(procedure: &mut BootProcedure<'_>, values: &[Result<u32, BusError>]) -> Vec<String> {
        let mut values = values.iter().cloned();
        let mut log = Vec::new();
        loop {
            match procedure.action() {
                Action::Read { index, subindex } => {
                    log.push(std::format!("read {index:04X}:{subindex}"));
                    procedure.read(values.next().expect("a value"));
                }
                Action::Write { index, data, .. } => {
                    log.push(std::format!("write {index:04X} {data:?}"));
                    procedure.wrote(Ok(()));
                }
                Action::Nmt(command) => {
                    log.push(std::format!("{command:?}"));
                    procedure.sent(Ok(()));
                }
                Action::Finished => return log,
            }
        }
    }

    #[test]
    fn a_node_is_probed_checked_configured_and_started() {
        let plan = plan();
        let mut procedure = BootProcedure::new(&plan);
        let log = run(&mut procedure, &[Ok(0x192), Ok(0x515), Ok(2)]);
        assert_eq!(
            log,
            [
                "read 1000:0",
                "read 1018:1",
                "read 1018:3",
                "write 1017 [100, 0]",
                "write 2000 [1, 2]",
                "Start"
            ]
        );
        let report = procedure.report();
        assert_eq!((report.device_type, report.result), (Some(0x192), Ok(())));
        assert_eq!(
            procedure.heartbeat_watch(),
            Some(core::time::Duration::from_millis(250))
        );
    }

    #[test]
    fn a_silent_node_is_missing_and_a_foreign_one_is_left_alone() {
        let plan = plan();
        let mut silent = BootProcedure::new(&plan);
        run(&mut silent, &[Err(BusError::Timeout)]);
        assert_eq!(silent.report().result, Err(BootError::Missing));
        let mut foreign = BootProcedure::new(&plan);
        let log = run(&mut foreign, &[Ok(0x192), Ok(0x99)]);
        assert_eq!(log.len(), 2, "nothing written: {log:?}");
        assert_eq!(
            foreign.report().result,
            Err(BootError::Foreign {
                subindex: 1,
                expected: 0x515,
                found: 0x99
            })
        );
    }

    #[test]
    fn an_aborted_write_is_reported_with_its_step_and_code() {
        let plan = plan();
        let mut procedure = BootProcedure::new(&plan);
        for value in [Ok(0x192), Ok(0x515), Ok(2)] {
            procedure.read(value);
        }
        procedure.wrote(Ok(()));
        let abort = BusError::SdoAbort {
            index: 0x2000,
            subindex: 0,
            code: AbortCode::ReadOnly,
        };
        procedure.wrote(Err(abort.clone()));
        assert_eq!(procedure.action(), Action::Finished);
        assert_eq!(
            procedure.report().result,
            Err(BootError::Step {
                step: BootStep::Write(0),
                error: abort
            })
        );
    }

    #[test]
    fn a_bare_plan_probes_and_starts() {
        let plan = NodeBoot::new(NodeId(1));
        let mut procedure = BootProcedure::new(&plan);
        assert_eq!(run(&mut procedure, &[Ok(1)]), ["read 1000:0", "Start"]);
        let plan = NodeBoot {
            start: false,
            ..NodeBoot::new(NodeId(1))
        };
        let mut procedure = BootProcedure::new(&plan);
        assert_eq!(run(&mut procedure, &[Ok(1)]), ["read 1000:0"]);
        assert_eq!(procedure.report().result, Ok(()));
    }
}
