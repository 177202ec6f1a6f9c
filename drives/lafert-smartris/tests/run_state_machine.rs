//! The Modbus-mode state machine (Modbus manual §4.2.1, Table 3) emitted as data, walked by the
//! drivebus planner against a register-level double of the drive, and the generated CiA 402
//! methods over the in-memory CANopen bus.

use std::time::{Duration, Instant};

use drivebus::control::driver::{ControlError, StuckReason};
use drivebus::control::{Plan, State};
use drivebus::modbus::{ModbusLink, RegisterBus, Table, UnitId};
use drivebus::testing::MemoryBus;
use drivebus::BusError;
use lafert_smartris::modbus_run::{self, MACHINE};
use lafert_smartris::Smartris;

const CONTROL_WORD: u16 = 0x0001;
const DRIVE_STATUS: u16 = 0x0060;

/// A Smartris in Modbus command mode: control word writes move the drive status as Table 3 says.
struct SmartrisDouble {
    registers: MemoryBus,
    commands: Vec<u16>,
}

impl SmartrisDouble {
    fn in_status(status: u16) -> Self {
        let mut registers = MemoryBus::new();
        registers
            .set_register(Table::Input, DRIVE_STATUS, status)
            .set_register(Table::Holding, CONTROL_WORD, 0);
        Self {
            registers,
            commands: Vec::new(),
        }
    }

    fn status(&self) -> u16 {
        self.registers
            .register(Table::Input, DRIVE_STATUS)
            .unwrap_or(0)
    }
}

impl RegisterBus for SmartrisDouble {
    fn read_registers(
        &mut self,
        unit: UnitId,
        table: Table,
        start: u16,
        out: &mut [u16],
    ) -> Result<(), BusError> {
        self.registers.read_registers(unit, table, start, out)
    }

    fn write_register(&mut self, unit: UnitId, address: u16, value: u16) -> Result<(), BusError> {
        if address == CONTROL_WORD {
            self.commands.push(value);
            let next = match (self.status(), value) {
                (0x0002 | 0x0004, 0x0003) => 0x0001, // T2, T5: run (velocity mode)
                (0x0001, 0x0001) => 0x0004,          // T4: stop
                (0x0001 | 0x0004, 0x0002) => 0x0002, // T3, T6: standby
                (unchanged, _) => unchanged,
            };
            self.registers
                .set_register(Table::Input, DRIVE_STATUS, next);
        }
        self.registers.write_register(unit, address, value)
    }

    fn write_registers(
        &mut self,
        unit: UnitId,
        start: u16,
        values: &[u16],
    ) -> Result<(), BusError> {
        self.registers.write_registers(unit, start, values)
    }
}

fn soon() -> Instant {
    Instant::now() + Duration::from_secs(2)
}

fn drive(status: u16) -> Smartris<ModbusLink<SmartrisDouble>> {
    Smartris::modbus(SmartrisDouble::in_status(status), UnitId(1))
}

fn commands(drive: Smartris<ModbusLink<SmartrisDouble>>) -> Vec<u16> {
    drive.into_link().into_bus().commands
}

#[test]
fn drive_status_values_of_the_manual_are_recognised() {
    // Manual §2.2, line 367: 0x0001 run velocity, 0x0002 standby, 0x0004 stop, 0x0010 alarm,
    // 0x0020 run torque, 0x0040 init, 0x0080 safe.
    let expected = [
        (0x0001, modbus_run::State::Run),
        (0x0002, modbus_run::State::Standby),
        (0x0004, modbus_run::State::Stop),
        (0x0010, modbus_run::State::Fault),
        (0x0020, modbus_run::State::Run),
        (0x0040, modbus_run::State::Init),
        (0x0080, modbus_run::State::Safety),
        (0x0082, modbus_run::State::Safety),
    ];
    for (status, state) in expected {
        assert_eq!(
            modbus_run::State::from_status(status),
            Some(state),
            "{status:#06x}"
        );
    }
    assert_eq!(modbus_run::State::from_status(0x0000), None);
}

#[test]
fn run_stop_and_standby_are_the_manual_s_control_word_values() {
    let mut standby = drive(0x0002);
    standby
        .goto_modbus_run(modbus_run::State::Run, soon())
        .unwrap();
    standby
        .goto_modbus_run(modbus_run::State::Stop, soon())
        .unwrap();
    standby
        .goto_modbus_run(modbus_run::State::Run, soon())
        .unwrap();
    standby
        .goto_modbus_run(modbus_run::State::Standby, soon())
        .unwrap();
    assert_eq!(
        standby.modbus_run_state(),
        Ok(Some(modbus_run::State::Standby))
    );
    // T2 0x0003, T4 0x0001, T5 0x0003, T3 0x0002 (manual lines 1204, 1215, 1219).
    assert_eq!(commands(standby), [0x0003, 0x0001, 0x0003, 0x0002]);
}

#[test]
fn fault_needs_the_reset_input_and_says_so() {
    let mut faulted = drive(0x0010);
    let error = faulted
        .goto_modbus_run(modbus_run::State::Run, soon())
        .unwrap_err();
    match error {
        ControlError::Stuck {
            state: Some("fault"),
            reason: StuckReason::NeedsExternal(t),
            ..
        } => {
            assert_eq!(t.name, "T9")
        }
        other => panic!("expected stuck in fault on T9, got {other}"),
    }
    assert!(
        commands(faulted).is_empty(),
        "nothing is written to a drive in alarm"
    );
}

#[test]
fn safety_is_left_only_by_releasing_sto() {
    let plan = MACHINE.next(
        modbus_run::State::Safety as u8,
        modbus_run::State::Run as u8,
        |_| true,
    );
    assert!(
        matches!(plan, Plan::NeedsExternal(t) if t.name == "safety-release"),
        "{plan:?}"
    );
}

#[test]
fn a_drive_that_ignores_the_command_times_out_naming_the_transition() {
    // Init does not leave by itself in the double: T1 is automatic, so the driver waits for it.
    let mut booting = drive(0x0040);
    let deadline = Instant::now() + Duration::from_millis(50);
    let error = booting
        .goto_modbus_run(modbus_run::State::Run, deadline)
        .unwrap_err();
    assert!(
        matches!(error, ControlError::Stuck { state: Some("init"), reason: StuckReason::Awaiting(t), .. } if t.name == "T1"),
        "{error}"
    );
}

#[test]
fn cia402_methods_are_generated_for_the_canopen_side() {
    let mut bus = MemoryBus::new();
    bus.set_object(0x6040, 0, &[0x00, 0x00])
        .set_object(0x6041, 0, &0x0240u16.to_le_bytes());
    let mut drive = Smartris::canopen(bus, drivebus::canopen::NodeId(1));
    assert_eq!(drive.cia402_state(), Ok(Some(State::SwitchOnDisabled)));
    // The in-memory bus never changes the statusword: the driver reports where it is stuck.
    let deadline = Instant::now() + Duration::from_millis(20);
    match drive.enable_operation(deadline).unwrap_err() {
        ControlError::Stuck {
            state: Some("switch on disabled"),
            reason:
                StuckReason::NoResponse {
                    transition,
                    command,
                },
            ..
        } => {
            assert_eq!((transition.name, command), ("2", 0x0006))
        }
        other => panic!("expected no response to shutdown, got {other}"),
    }
    let mut link = drive.into_link();
    assert_eq!(link.bus_mut().object(0x6040, 0), Some(&[0x06, 0x00][..]));
}
