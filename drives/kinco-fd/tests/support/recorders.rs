//! Buses that answer from a `MemoryBus` and record what would go on the wire: Modbus RTU frames
//! (unit, PDU, CRC) as `drivebus::modbus::rtu` encodes them, and the first CAN frame of every
//! SDO transfer as drivebus' sans-I/O SDO client builds it.

#![allow(dead_code)] // each test file uses one of the two

use drivebus::memory::MemoryBus;
use drivebus::modbus::pdu::Request;
use drivebus::modbus::rtu::{encode_request, MAX_ADU};
use drivebus::modbus::{RegisterBus, Table, UnitId};
use drivebus::BusError;

/// Records RTU frames, answers from `memory`.
#[derive(Debug, Default)]
pub struct RtuRecorder {
    pub memory: MemoryBus,
    pub frames: Vec<Vec<u8>>,
}

impl RtuRecorder {
    fn record(&mut self, unit: UnitId, request: &Request<'_>) -> Result<(), BusError> {
        let mut frame = [0u8; MAX_ADU];
        let len = encode_request(unit, request, &mut frame)?;
        self.frames.push(frame[..len].to_vec());
        Ok(())
    }
}

impl RegisterBus for RtuRecorder {
    fn read_registers(
        &mut self,
        unit: UnitId,
        table: Table,
        start: u16,
        out: &mut [u16],
    ) -> Result<(), BusError> {
        let count = out.len() as u16;
        let request = match table {
            Table::Input => Request::ReadInputRegisters { start, count },
            _ => Request::ReadHoldingRegisters { start, count },
        };
        self.record(unit, &request)?;
        self.memory.read_registers(unit, table, start, out)
    }

    fn write_register(&mut self, unit: UnitId, address: u16, value: u16) -> Result<(), BusError> {
        self.record(unit, &Request::WriteSingleRegister { address, value })?;
        self.memory.write_register(unit, address, value)
    }

    fn write_registers(
        &mut self,
        unit: UnitId,
        start: u16,
        values: &[u16],
    ) -> Result<(), BusError> {
        self.record(unit, &Request::WriteMultipleRegisters { start, values })?;
        self.memory.write_registers(unit, start, values)
    }
}
