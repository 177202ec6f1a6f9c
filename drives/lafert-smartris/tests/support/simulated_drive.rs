//! A scripted Smartris for the helper tests: a `MemoryBus` register map plus the macro state
//! machine of the Modbus manual §4.2.1 Table 3 (lines 1224-1232) driven by control word writes,
//! and a reboot after a system reset during which the drive is silent.

// Each test binary uses a part of the double.
#![allow(dead_code)]

use drivebus::modbus::{RegisterBus, Table, UnitId};
use drivebus::testing::MemoryBus;
use drivebus::BusError;

pub const CONTROL_WORD: u16 = 0x0001;
pub const STORE: u16 = 0x0000;
pub const RESET: u16 = 0xA5A5;
pub const OPERATION_MODE: u16 = 0x0207;
pub const DRIVE_STATUS: u16 = 0x0060;
pub const ERROR_CODE: u16 = 0x0063;
/// FULL SCALE VELOCITY, the bound of the speed setpoint (an L motor: 3000 rpm).
pub const FULL_SCALE_VELOCITY: u16 = 0x0003;

pub const RUN_VELOCITY: u16 = 0x0001;
pub const STANDBY: u16 = 0x0002;
pub const STOP: u16 = 0x0004;
pub const ALARM: u16 = 0x0010;
pub const RUN_TORQUE: u16 = 0x0020;
pub const SAFE: u16 = 0x0080;

/// The scripted drive.
#[derive(Debug)]
pub struct SimulatedDrive {
    pub memory: MemoryBus,
    /// How many requests after a reset time out before the drive answers again.
    pub silent_requests_after_reset: u32,
    /// Whether the drive obeys run commands (a drive with the brake stuck does not).
    pub obeys_run: bool,
    /// Whether the drive reboots before it answers the reset command.
    pub reset_unanswered: bool,
    silent_left: u32,
}

impl SimulatedDrive {
    /// A drive in standby, in `operation_mode` (1 torque, 2 velocity), without an error.
    pub fn in_standby(operation_mode: u16) -> Self {
        let mut memory = MemoryBus::new();
        for address in [CONTROL_WORD, STORE, RESET, 0x0028, 0x0042, 0x0047] {
            memory.set_register(Table::Holding, address, 0);
        }
        memory
            .set_register(Table::Holding, OPERATION_MODE, operation_mode)
            .set_register(Table::Holding, FULL_SCALE_VELOCITY, 3000)
            .set_register(Table::Input, DRIVE_STATUS, STANDBY)
            .set_register(Table::Input, ERROR_CODE, 0);
        Self {
            memory,
            silent_requests_after_reset: 0,
            obeys_run: true,
            reset_unanswered: false,
            silent_left: 0,
        }
    }

    /// Puts the drive in alarm with `code` (input 0x0063).
    pub fn with_alarm(mut self, code: u16) -> Self {
        self.memory
            .set_register(Table::Input, DRIVE_STATUS, ALARM)
            .set_register(Table::Input, ERROR_CODE, code);
        self
    }

    /// Overrides the drive status.
    pub fn with_status(mut self, status: u16) -> Self {
        self.memory.set_register(Table::Input, DRIVE_STATUS, status);
        self
    }

    pub fn status(&self) -> u16 {
        self.memory.register(Table::Input, DRIVE_STATUS).unwrap()
    }

    /// Holding register writes, in order, as (address, value).
    pub fn writes(&self) -> Vec<(u16, u16)> {
        self.memory
            .log()
            .iter()
            .filter_map(|request| match request {
                drivebus::testing::Request::Write { start, values } => Some((*start, values[0])),
                _ => None,
            })
            .collect()
    }

    fn silent(&mut self) -> Result<(), BusError> {
        if self.silent_left > 0 {
            self.silent_left -= 1;
            return Err(BusError::Timeout);
        }
        Ok(())
    }

    /// Table 3: T2/T5 run (0x0003), T4 stop (0x0001), T3/T6 standby (0x0002).
    fn obey_control_word(&mut self, value: u16) {
        let status = self.status();
        if status & (ALARM | SAFE) != 0 {
            return;
        }
        let run = match self.memory.register(Table::Holding, OPERATION_MODE) {
            Some(1) => RUN_TORQUE,
            _ => RUN_VELOCITY,
        };
        let next = match value {
            0x0003 if self.obeys_run => run,
            0x0001 if status & (RUN_TORQUE | RUN_VELOCITY) != 0 => STOP,
            0x0002 => STANDBY,
            _ => status,
        };
        self.memory.set_register(Table::Input, DRIVE_STATUS, next);
    }
}

impl RegisterBus for SimulatedDrive {
    fn read_registers(
        &mut self,
        unit: UnitId,
        table: Table,
        start: u16,
        out: &mut [u16],
    ) -> Result<(), BusError> {
        self.silent()?;
        self.memory.read_registers(unit, table, start, out)
    }

    fn write_register(&mut self, unit: UnitId, address: u16, value: u16) -> Result<(), BusError> {
        self.silent()?;
        self.memory.write_register(unit, address, value)?;
        match address {
            CONTROL_WORD => self.obey_control_word(value),
            RESET => {
                self.silent_left = self.silent_requests_after_reset;
                self.memory
                    .set_register(Table::Input, DRIVE_STATUS, STANDBY);
            }
            _ => {}
        }
        Ok(())
    }

    /// The Smartris has no FC 0x10.
    fn write_registers(&mut self, _: UnitId, _: u16, _: &[u16]) -> Result<(), BusError> {
        Err(BusError::Unsupported("FC 0x10 on a Smartris"))
    }
}
