//! A scripted smd for the session tests: a `MemoryBus` register map plus the unlock rules of
//! sections 4.5 and 4.6 (lines 405-425) and Note 1 (lines 567-571): writes while locked answer
//! exception 01, #48 = 0 unlocks controls, #48 or #49 = the password C94 unlocks parameters too,
//! #1 bit 1 locks, and #1 with several bits obeys only STOP or answers exception 04.

// Each test binary uses a part of the double.
#![allow(dead_code)]

use drivebus::modbus::{RegisterBus, Table, UnitId};
use drivebus::testing::MemoryBus;
use drivebus::BusError;

pub const DRIVE_CONTROL: u16 = 1;
pub const SERIAL_SPEED: u16 = 40;
pub const UNLOCK_CONTROLS: u16 = 48;
pub const UNLOCK_PARAMETERS: u16 = 49;
pub const CONFIGURATION: u16 = 50;
pub const C01: u16 = 51;
pub const C10: u16 = 59;
pub const C11: u16 = 60;
pub const C12: u16 = 61;
/// C94 in PC507 (line 925).
pub const C94_PC507: u16 = 94;

const LOCK_BIT: u16 = 0x0002;
const STOP_BIT: u16 = 0x0004;

/// The scripted drive.
#[derive(Debug)]
pub struct SmdDouble {
    pub memory: MemoryBus,
    pub controls_unlocked: bool,
    pub parameters_unlocked: bool,
    /// Every write the drive accepted, in order.
    pub accepted: Vec<(u16, u16)>,
}

fn exception(code: u8) -> BusError {
    BusError::ModbusException {
        function: 0x06,
        code: code.into(),
    }
}

impl SmdDouble {
    /// A PC507 drive (#50 = 507) with C01 = `c01`, C10 = 0, C11 = 50.0 Hz, C94 = `password`.
    pub fn pc507(c01: u16, password: u16) -> Self {
        let mut memory = MemoryBus::new();
        for r in [
            DRIVE_CONTROL,
            SERIAL_SPEED,
            UNLOCK_CONTROLS,
            UNLOCK_PARAMETERS,
            C12,
        ] {
            memory.set_register(Table::Holding, r, 0);
        }
        for r in 24..=29 {
            memory.set_register(Table::Holding, r, 0);
        }
        memory
            .set_register(Table::Holding, CONFIGURATION, 507)
            .set_register(Table::Holding, C01, c01)
            .set_register(Table::Holding, C10, 0)
            .set_register(Table::Holding, C11, 500)
            .set_register(Table::Holding, C94_PC507, password);
        Self {
            memory,
            controls_unlocked: false,
            parameters_unlocked: false,
            accepted: Vec::new(),
        }
    }

    fn password(&self) -> u16 {
        self.memory
            .register(Table::Holding, C94_PC507)
            .unwrap_or_default()
    }

    /// Whether the rules allow writing `value` to `address` now; applies unlocks and locks.
    fn admit(&mut self, address: u16, value: u16) -> Result<(), BusError> {
        match address {
            UNLOCK_CONTROLS => {
                self.controls_unlocked |= value == 0 || value == self.password();
                self.parameters_unlocked |= value == self.password();
            }
            UNLOCK_PARAMETERS => self.parameters_unlocked |= value == self.password(),
            // Lock ends a parameter session too (section 5.8, line 801).
            DRIVE_CONTROL if value == LOCK_BIT && self.parameters_unlocked => {
                self.controls_unlocked = false;
                self.parameters_unlocked = false;
            }
            DRIVE_CONTROL | SERIAL_SPEED if !self.controls_unlocked => return Err(exception(1)),
            DRIVE_CONTROL if value.count_ones() > 1 && value & STOP_BIT == 0 => {
                return Err(exception(4))
            }
            DRIVE_CONTROL if value & LOCK_BIT != 0 => {
                self.controls_unlocked = false;
                self.parameters_unlocked = false;
            }
            DRIVE_CONTROL | SERIAL_SPEED => {}
            _ if !self.parameters_unlocked => return Err(exception(1)),
            _ => {}
        }
        self.accepted.push((address, value));
        Ok(())
    }
}

impl RegisterBus for SmdDouble {
    fn read_registers(
        &mut self,
        unit: UnitId,
        table: Table,
        start: u16,
        out: &mut [u16],
    ) -> Result<(), BusError> {
        self.memory.read_registers(unit, table, start, out)
    }

    fn write_register(&mut self, unit: UnitId, address: u16, value: u16) -> Result<(), BusError> {
        self.admit(address, value)?;
        self.memory.write_register(unit, address, value)
    }

    /// The link writes single words with FC 0x06; FC 0x10 is never needed here.
    fn write_registers(&mut self, _: UnitId, _: u16, _: &[u16]) -> Result<(), BusError> {
        Err(BusError::Unsupported("FC 0x10 in the session double"))
    }
}
