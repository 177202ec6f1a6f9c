//! The sans-I/O boot of one node: which request comes next, given how the last one went.

use super::item::Item;
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

/// Where the current item (heartbeat, PDO, boot parameter) is: comparing its objects, or
/// writing them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    Check(usize),
    Write(usize),
}

/// The boot of one node as a sequence of requests. Each configuration item is read and
/// compared before it is written, and written only where the node does not hold it already.
#[derive(Debug, Clone)]
pub struct BootProcedure<'a> {
    plan: &'a NodeBoot,
    step: BootStep,
    item: Item,
    phase: Phase,
    device_type: Option<u32>,
    outcome: Option<Result<(), BootError>>,
    written: usize,
    unchanged: usize,
}

impl<'a> BootProcedure<'a> {
    /// The boot `plan` describes, not started.
    pub fn new(plan: &'a NodeBoot) -> Self {
        Self {
            plan,
            step: BootStep::Probe,
            item: Item::default(),
            phase: Phase::Check(0),
            device_type: None,
            outcome: None,
            written: 0,
            unchanged: 0,
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
            BootStep::Heartbeat | BootStep::Pdo(_) | BootStep::Write(_) => self.item_action(),
            BootStep::Start => Action::Nmt(NmtCommand::Start),
        }
    }

    fn item_action(&self) -> Action<'_> {
        match self.phase {
            Phase::Check(j) => {
                let write = &self.item.checks[j].write;
                Action::Read {
                    index: write.index,
                    subindex: write.subindex,
                }
            }
            Phase::Write(j) => {
                let write = &self.item.writes[j];
                Action::Write {
                    index: write.index,
                    subindex: write.subindex,
                    data: &write.data,
                }
            }
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
            (BootStep::Heartbeat | BootStep::Pdo(_) | BootStep::Write(_), value) => {
                self.compared(value)
            }
            (step, Err(error)) => self.finish(Err(BootError::Step { step, error })),
            (_, Ok(_)) => self.advance(),
        }
    }

    /// An item's object read back: the next check if it holds its value, the writes if not
    /// (or if the node refused the read: the write then says why, or sets it).
    fn compared(&mut self, value: Result<u32, BusError>) {
        let Phase::Check(j) = self.phase else {
            return;
        };
        match value {
            Ok(found) if self.item.checks[j].holds(found) => {
                if j + 1 < self.item.checks.len() {
                    self.phase = Phase::Check(j + 1);
                } else {
                    self.unchanged += 1;
                    self.advance();
                }
            }
            Ok(_) | Err(BusError::SdoAbort { .. }) => self.phase = Phase::Write(0),
            Err(error) => self.finish(Err(BootError::Step {
                step: self.step,
                error,
            })),
        }
    }

    /// How the last [`Action::Write`] went.
    pub fn wrote(&mut self, result: Result<(), BusError>) {
        if let Err(error) = result {
            return self.finish(Err(BootError::Step {
                step: self.step,
                error,
            }));
        }
        match self.phase {
            Phase::Write(j) if j + 1 < self.item.writes.len() => self.phase = Phase::Write(j + 1),
            Phase::Write(_) => {
                self.written += 1;
                self.advance();
            }
            Phase::Check(_) => self.advance(),
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
            written: self.written,
            unchanged: self.unchanged,
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

    /// Moves to the next step the plan asks for and loads its item; after the last one the
    /// boot is done.
    fn advance(&mut self) {
        let mut next = self.following(self.step);
        while let Some(step) = next.filter(|s| !self.wanted(*s)) {
            next = self.following(step);
        }
        let Some(step) = next else {
            return self.finish(Ok(()));
        };
        self.step = step;
        let item = match step {
            BootStep::Heartbeat => Ok(Item::heartbeat(self.plan)),
            BootStep::Pdo(n) => Item::pdo(&self.plan.pdos[n]),
            BootStep::Write(n) => Ok(Item::single(self.plan.writes[n].clone())),
            // Not an item: its answer moves on (`wrote` in `Phase::Check`).
            _ => Ok(Item::default()),
        };
        match item {
            Ok(item) => {
                let unreadable = item.checks.is_empty() && !item.writes.is_empty();
                self.phase = match unreadable {
                    true => Phase::Write(0),
                    false => Phase::Check(0),
                };
                self.item = item;
            }
            Err(error) => self.finish(Err(BootError::Step { step, error })),
        }
    }

    /// The step after `step` in the full sequence.
    fn following(&self, step: BootStep) -> Option<BootStep> {
        Some(match step {
            BootStep::Probe => BootStep::Identity(1),
            BootStep::Identity(sub) if sub < 3 => BootStep::Identity(sub + 1),
            BootStep::Identity(_) => BootStep::Heartbeat,
            BootStep::Heartbeat => BootStep::Pdo(0),
            BootStep::Pdo(n) if n + 1 < self.plan.pdos.len() => BootStep::Pdo(n + 1),
            BootStep::Pdo(_) => BootStep::Write(0),
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
            BootStep::Pdo(n) => n < self.plan.pdos.len(),
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
    use crate::canopen::pdo::{MappedObject, PdoKind, PdoSetup};
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
            pdos: vec![],
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
        let log = run(&mut procedure, &[Ok(0x192), Ok(0x515), Ok(2), Ok(0), Ok(0)]);
        assert_eq!(
            log,
            [
                "read 1000:0",
                "read 1018:1",
                "read 1018:3",
                "read 1017:0",
                "write 1017 [100, 0]",
                "read 2000:0",
                "write 2000 [1, 2]",
                "Start"
            ]
        );
        let report = procedure.report();
        assert_eq!((report.device_type, report.result), (Some(0x192), Ok(())));
        assert_eq!((report.written, report.unchanged), (2, 0));
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
        for value in [Ok(0x192), Ok(0x515), Ok(2), Ok(0)] {
            procedure.read(value);
        }
        procedure.wrote(Ok(()));
        procedure.read(Ok(0x0102)); // another value: written
        assert!(matches!(procedure.action(), Action::Write { .. }));
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
    fn what_the_node_holds_already_is_not_written() {
        let mut plan = plan();
        plan.pdos.push(PdoSetup {
            kind: PdoKind::Transmit,
            number: 1,
            cob_id: 0x184,
            transmission_type: Some(254),
            inhibit_time: None,
            event_timer: None,
            entries: vec![MappedObject::new(0x6041, 0, 16)],
        });
        let mut procedure = BootProcedure::new(&plan);
        // The node holds heartbeat 100 ms, TPDO1 as planned (its COB-ID with bit 30 set, as
        // devices report it) and 2000h = 0201h.
        let held = [
            Ok(0x192),
            Ok(0x515),
            Ok(2),
            Ok(100),
            Ok(0x4000_0184),
            Ok(254),
            Ok(1),
        ];
        let log = run(
            &mut procedure,
            &[&held[..], &[Ok(0x6041_0010), Ok(0x0201)]].concat(),
        );
        assert!(log.iter().all(|l| !l.starts_with("write")), "{log:?}");
        let report = procedure.report();
        assert_eq!(
            (report.result, report.written, report.unchanged),
            (Ok(()), 0, 3)
        );
    }

    #[test]
    fn a_pdo_that_differs_in_one_object_is_configured_whole() {
        let mut plan = plan();
        plan.heartbeat = None;
        plan.writes.clear();
        plan.pdos.push(PdoSetup {
            kind: PdoKind::Receive,
            number: 2,
            cob_id: 0x304,
            transmission_type: None,
            inhibit_time: None,
            event_timer: None,
            entries: vec![MappedObject::new(0x6040, 0, 16)],
        });
        let mut procedure = BootProcedure::new(&plan);
        // The COB-ID is the same, the count differs: disable, map, enable.
        let log = run(
            &mut procedure,
            &[Ok(0x192), Ok(0x515), Ok(2), Ok(0x304), Ok(2)],
        );
        assert_eq!(
            &log[3..],
            [
                "read 1401:1",
                "read 1601:0",
                "write 1401 [4, 3, 0, 128]",
                "write 1601 [0]",
                "write 1601 [16, 0, 64, 96]",
                "write 1601 [1]",
                "write 1401 [4, 3, 0, 0]",
                "Start"
            ]
        );
        assert_eq!(procedure.report().written, 1);
    }

    #[test]
    fn a_refused_pdo_write_is_reported_with_the_pdo_step() {
        let mut plan = plan();
        plan.pdos.push(PdoSetup {
            kind: PdoKind::Transmit,
            number: 600,
            cob_id: 0x184,
            transmission_type: None,
            inhibit_time: None,
            event_timer: None,
            entries: vec![],
        });
        let mut procedure = BootProcedure::new(&plan);
        run(&mut procedure, &[Ok(0x192), Ok(0x515), Ok(2), Ok(100)]);
        assert!(matches!(
            procedure.report().result,
            Err(BootError::Step {
                step: BootStep::Pdo(0),
                error: BusError::Unsupported(_)
            })
        ));
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
