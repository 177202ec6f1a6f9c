//! The CiA 402 controlword's stopping commands (profile `stops`: disable voltage, quick stop,
//! anything without enable operation, halt) go out while the handle refuses writes; enabling
//! operation does not. Kinco's own words (line 1935): 0x06 power off, 0x0B quick stop, 0x0F
//! power on. A quick stop by option code goes out even when the code (605Ah) cannot be read,
//! and before it is read: a code that answers slowly, or never, does not hold the stop back.

use std::time::{Duration, Instant};

use drivebus::asynch::TokioTimer;
use drivebus::control::ControlError;
use drivebus::modbus::{AsyncRegisterBus, RegisterBus, Table, UnitId};
use drivebus::testing::{MemoryBus, Request};
use drivebus::{BusError, Error, WriteRefusal};
use kinco_fd::KincoFd;

#[test]
fn power_off_quick_stop_and_halt_go_out_power_on_does_not() {
    let mut bus = MemoryBus::new();
    bus.set_register(Table::Holding, 0x3100, 0);
    let mut drive = KincoFd::modbus(bus, UnitId(1));
    // What the client believes (an identity it could not confirm, say): every write refused.
    let belief = WriteRefusal::IdentityMismatch {
        parameter: "vendor_id",
        expected: &[0x0000_0300],
        found: 0,
    };
    drive.device().refuse_writes(belief);
    assert_eq!(
        drive.controlword().write_raw(0x000F),
        Err(Error::WritesRefused {
            parameter: "controlword",
            reason: belief
        })
    );
    for stop in [0x0006, 0x000B, 0x0000, 0x010F] {
        assert_eq!(drive.controlword().write_raw(stop), Ok(()), "{stop:#06x}");
    }
    let written = controlwords(&mut drive);
    assert_eq!(written, [0x0006, 0x000B, 0x0000, 0x010F]);
}

/// The controlword values written to holding 0x3100, in order.
fn controlwords(drive: &mut KincoFd<drivebus::modbus::ModbusLink<MemoryBus>>) -> Vec<u16> {
    let log = drive.device().link_mut().bus_mut().log();
    log.iter()
        .filter_map(|r| match r {
            Request::Write {
                start: 0x3100,
                values,
            } => values.first().copied(),
            _ => None,
        })
        .collect()
}

#[test]
fn a_quick_stop_by_option_code_goes_out_when_the_code_cannot_be_read() {
    let mut bus = MemoryBus::new();
    // Operation enabled; no register 0x3400 (605Ah): its read is refused.
    bus.set_register(Table::Holding, 0x3100, 0x000F);
    bus.set_register(Table::Holding, 0x3200, 0x0027);
    let mut drive = KincoFd::modbus(bus, UnitId(1));
    assert!(drive.quick_stop_mode().read().is_err());
    let outcome = drive.quick_stop_by_option_code(Instant::now() + Duration::from_millis(50));
    // The memory never leaves operation enabled, so the walk ends stuck; the command went out.
    assert!(
        matches!(outcome, Err(ControlError::Stuck { .. })),
        "{outcome:?}"
    );
    // The quick stop command (CiA 402: bit 1 set, bits 2 and 7 clear; Kinco's 0x0B is one).
    let first = controlwords(&mut drive).first().copied();
    assert_eq!(first.map(|c| c & 0x0086), Some(0x0002), "{first:x?}");
}

/// How long the read of 605Ah (holding 0x3400) takes before it fails with a timeout.
const CODE_TIMEOUT: Duration = Duration::from_millis(300);

/// A drive in operation enabled (in memory) whose quick stop option code never answers: its
/// read fails with a timeout after [`CODE_TIMEOUT`], slept on the thread (blocking) or on
/// tokio's clock (async). Every request, the code's read too, lands in the memory's log, and
/// each controlword write is timed.
struct SilentCode {
    memory: MemoryBus,
    started: tokio::time::Instant,
    /// The controlwords written, with when, since `started`.
    writes: Vec<(u16, Duration)>,
}

impl SilentCode {
    fn new() -> Self {
        let mut memory = MemoryBus::new();
        memory.set_register(Table::Holding, 0x3100, 0x000F);
        memory.set_register(Table::Holding, 0x3200, 0x0027);
        Self {
            memory,
            started: tokio::time::Instant::now(),
            writes: Vec::new(),
        }
    }

    /// Whether `start` is the quick stop option code's register.
    fn is_code(start: u16) -> bool {
        start == 0x3400
    }

    /// Reads from memory; the code's read is logged and times out.
    fn read(&mut self, unit: UnitId, table: Table, at: u16, out: &mut [u16]) -> Answer {
        let read = self.memory.read_registers(unit, table, at, out);
        read.and(if Self::is_code(at) {
            Err(BusError::Timeout)
        } else {
            Ok(())
        })
    }

    fn write(&mut self, unit: UnitId, start: u16, values: &[u16]) -> Answer {
        if let (0x3100, Some(&value)) = (start, values.first()) {
            self.writes.push((value, self.started.elapsed()));
        }
        self.memory.write_registers(unit, start, values)
    }

    /// Checks the quick stop command was the first write, at once, and went out before the
    /// code's read.
    fn assert_commanded_first(&self) {
        let (first, at) = self.writes.first().copied().expect("a controlword write");
        // CiA 402's quick stop: bit 1 set, bits 2 and 7 clear (Kinco's 0x0B is one).
        assert_eq!(first & 0x0086, 0x0002, "{first:#06x}");
        assert!(at < CODE_TIMEOUT, "the stop waited for the code: {at:?}");
        let log = self.memory.log();
        let command = log
            .iter()
            .position(|r| matches!(r, Request::Write { start: 0x3100, .. }));
        let code = log
            .iter()
            .position(|r| matches!(r, Request::Read { start, .. } if Self::is_code(*start)));
        assert!(command.is_some(), "{log:?}");
        assert!(
            code.is_none() || command < code,
            "the code was read first: {log:?}"
        );
    }
}

/// What a request of [`SilentCode`] answers.
type Answer = Result<(), BusError>;

impl RegisterBus for SilentCode {
    fn read_registers(&mut self, u: UnitId, t: Table, at: u16, out: &mut [u16]) -> Answer {
        if Self::is_code(at) {
            std::thread::sleep(CODE_TIMEOUT);
        }
        self.read(u, t, at, out)
    }
    fn write_register(&mut self, u: UnitId, at: u16, value: u16) -> Answer {
        self.write(u, at, &[value])
    }
    fn write_registers(&mut self, u: UnitId, at: u16, values: &[u16]) -> Answer {
        self.write(u, at, values)
    }
}

impl AsyncRegisterBus for SilentCode {
    async fn read_registers(&mut self, u: UnitId, t: Table, at: u16, out: &mut [u16]) -> Answer {
        if Self::is_code(at) {
            tokio::time::sleep(CODE_TIMEOUT).await;
        }
        self.read(u, t, at, out)
    }
    async fn write_register(&mut self, u: UnitId, at: u16, value: u16) -> Answer {
        self.write(u, at, &[value])
    }
    async fn write_registers(&mut self, u: UnitId, at: u16, values: &[u16]) -> Answer {
        self.write(u, at, values)
    }
}

#[test]
fn a_quick_stop_by_option_code_goes_out_before_its_code_is_read() {
    let mut drive = KincoFd::modbus(SilentCode::new(), UnitId(1));
    let outcome = drive.quick_stop_by_option_code(Instant::now() + Duration::from_secs(1));
    // The memory never leaves operation enabled, so the walk ends stuck.
    assert!(
        matches!(outcome, Err(ControlError::Stuck { .. })),
        "{outcome:?}"
    );
    let bus = drive.device().link_mut().bus_mut();
    bus.assert_commanded_first();
    let code_reads = bus
        .memory
        .log()
        .iter()
        .filter(|r| matches!(r, Request::Read { start: 0x3400, .. }))
        .count();
    assert_eq!(code_reads, 1, "read once, after the command");
}

#[tokio::test(start_paused = true)]
async fn an_awaited_quick_stop_by_option_code_goes_out_at_once_and_keeps_its_limit() {
    let limit = Duration::from_millis(100);
    assert!(limit < CODE_TIMEOUT);
    let mut drive = KincoFd::modbus_async(SilentCode::new(), UnitId(1));
    let started = tokio::time::Instant::now();
    let outcome = drive
        .quick_stop_by_option_code_async(&TokioTimer, limit)
        .await;
    assert!(
        matches!(outcome, Err(ControlError::Stuck { .. })),
        "{outcome:?}"
    );
    // The code's read, under way when the limit passed, does not stretch the stop past it.
    assert_eq!(started.elapsed(), limit);
    let bus = drive.device().link_mut().get_mut().bus_mut();
    assert_eq!(bus.writes.first().map(|w| w.1), Some(Duration::ZERO));
    bus.assert_commanded_first();
}
