//! The sans-I/O Modbus server: a request PDU in, a response PDU out.

use drivebus::modbus::pdu::{self, Request};
use drivebus::modbus::Table;
use drivegen::ir::{Device, ModbusCaps};

use super::map::{self, Cell, RegisterMap};
use super::{command_register, read_blocks};
use crate::drive::Drive;
use crate::refusal::Refusal;

/// Exception code of an unsupported function.
const ILLEGAL_FUNCTION: u8 = 0x01;
/// Exception code of a malformed request or a count beyond the device's limits.
const ILLEGAL_DATA_VALUE: u8 = 0x03;
/// Function codes the request decoder knows.
const IMPLEMENTED: [u8; 8] = [0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x0F, 0x10];

/// Answers Modbus requests for one drive.
#[derive(Debug, Clone)]
pub struct ModbusServer {
    map: RegisterMap,
    caps: Option<ModbusCaps>,
}

/// Why a request was answered with an exception.
type Exception = u8;

impl ModbusServer {
    /// A server for `device` in `variant` (`None`: the default configuration).
    pub fn new(device: &Device, variant: Option<&str>) -> Self {
        Self {
            map: RegisterMap::new(device, variant),
            caps: device.modbus.clone(),
        }
    }

    /// Answers the request `request` (a PDU) into `out` (at least
    /// [`MAX_PDU`](drivebus::modbus::pdu::MAX_PDU) bytes); returns the length of the response PDU.
    pub fn handle(&self, drive: &mut Drive, request: &[u8], out: &mut [u8]) -> usize {
        drive.heard();
        let function = request.first().copied().unwrap_or(0);
        let answer = self.answer(drive, request, out);
        let result = match answer {
            Ok(len) => Ok(len),
            Err(code) => pdu::encode_exception(self.exception_function(function), code, out),
        };
        result.unwrap_or(0)
    }

    /// The function code whose exception flag makes the answer's function code: the request's
    /// own, or what the description declares the device answers instead (`exception_functions`).
    fn exception_function(&self, function: u8) -> u8 {
        self.caps
            .as_ref()
            .map_or(function, |c| c.exception_function(function) & 0x7F)
    }

    fn answer(
        &self,
        drive: &mut Drive,
        request: &[u8],
        out: &mut [u8],
    ) -> Result<usize, Exception> {
        let function = request.first().copied().unwrap_or(0);
        if !self.supports(function) {
            return Err(ILLEGAL_FUNCTION);
        }
        let decoded = pdu::decode_request(request).map_err(|_| {
            if IMPLEMENTED.contains(&function) {
                ILLEGAL_DATA_VALUE // A bad count, length or coil value.
            } else {
                ILLEGAL_FUNCTION
            }
        })?;
        match decoded {
            Request::ReadHoldingRegisters { start, count }
            | Request::ReadInputRegisters { start, count } => {
                let table = match decoded {
                    Request::ReadHoldingRegisters { .. } => Table::Holding,
                    // A device that does not tell 3X from 4X references (Lenze smd, line 237).
                    _ if self.input_reads_holding() => Table::Holding,
                    _ => Table::Input,
                };
                let values = self.read(drive, table, start, count)?;
                pdu::encode_registers_response(function, &values, out)
                    .map_err(|_| ILLEGAL_DATA_VALUE)
            }
            Request::WriteSingleRegister { address, value } => {
                self.write(drive, address, &[value])?;
                pdu::encode_write_response(request, out).map_err(|_| ILLEGAL_DATA_VALUE)
            }
            Request::WriteMultipleRegisters { start, values } => {
                let values: Vec<u16> = values.iter().collect();
                if values.len() > usize::from(self.max_write()) {
                    return Err(ILLEGAL_DATA_VALUE);
                }
                self.write(drive, start, &values)?;
                pdu::encode_write_response(request, out).map_err(|_| ILLEGAL_DATA_VALUE)
            }
            Request::ReadCoils { .. }
            | Request::ReadDiscreteInputs { .. }
            | Request::WriteSingleCoil { .. }
            | Request::WriteMultipleCoils { .. } => Err(self.exception(Refusal::NoSuchAddress)),
        }
    }

    fn supports(&self, function: u8) -> bool {
        self.caps
            .as_ref()
            .map_or(function != 0 && function <= 0x10, |c| {
                c.functions.contains(&function)
            })
    }

    /// Whether the drive executes a broadcast (unit id 0): as its description's `[modbus]
    /// broadcast` says, and always for a description without `[modbus]`.
    pub fn accepts_broadcast(&self) -> bool {
        self.caps.as_ref().is_none_or(|c| c.broadcast)
    }

    fn input_reads_holding(&self) -> bool {
        self.caps.as_ref().is_some_and(|c| c.input_reads_holding)
    }

    fn max_write(&self) -> u16 {
        self.caps
            .as_ref()
            .map_or(pdu::MAX_WRITE_REGISTERS, |c| c.max_write_registers)
    }

    fn exception(&self, refusal: Refusal) -> Exception {
        refusal.modbus_exception(self.caps.as_ref())
    }

    fn read(
        &self,
        drive: &Drive,
        table: Table,
        start: u16,
        count: u16,
    ) -> Result<Vec<u16>, Exception> {
        let max = self.caps.as_ref().map_or(125, |c| c.max_read_registers);
        if let Some(value) = read_blocks::whole_value(&self.map, drive, table, start, count) {
            return Ok(value);
        }
        if count > max && !read_blocks::is_block(self.caps.as_ref(), table, start, count) {
            return Err(ILLEGAL_DATA_VALUE);
        }
        let gaps = self.caps.as_ref().is_some_and(|c| c.read_gaps)
            || read_blocks::is_zero_fill(self.caps.as_ref(), table, start, count);
        let mut values = Vec::with_capacity(count as usize);
        let mut documented = false;
        for address in (0..count).map(|i| start.wrapping_add(i)) {
            let Some(cell) = self.map.cell(table, address) else {
                if gaps {
                    values.push(0);
                    continue;
                }
                return Err(self.exception(Refusal::NoSuchAddress));
            };
            if !cell.access.read {
                return Err(self.exception(Refusal::WriteOnly));
            }
            documented = true;
            values.push(map::registers(drive.store(), cell)[(address - cell.first) as usize]);
        }
        if !documented {
            // Gaps are tolerated inside a read, not as the whole of it.
            return Err(self.exception(Refusal::NoSuchAddress));
        }
        Ok(values)
    }

    /// Writes `values` from `start`, parameter by parameter; every register is checked before
    /// anything is stored.
    fn write(&self, drive: &mut Drive, start: u16, values: &[u16]) -> Result<(), Exception> {
        let mut writes: Vec<(Cell, Vec<u16>)> = Vec::new();
        for (i, &value) in values.iter().enumerate() {
            let address = start.wrapping_add(i as u16);
            let cell = self
                .map
                .cell(Table::Holding, address)
                .ok_or(self.exception(Refusal::NoSuchAddress))?;
            let value =
                command_register::combined(drive.store(), self.caps.as_ref(), address, value)?;
            let cell = command_register::matching(drive.store(), cell, address, value);
            if !cell.access.write {
                return Err(self.exception(Refusal::ReadOnly));
            }
            if writes.last().is_none_or(|(c, _)| c.id != cell.id) {
                writes.push((cell, map::registers(drive.store(), cell)));
            }
            if let Some((_, regs)) = writes.last_mut() {
                regs[(address - cell.first) as usize] = value;
            }
        }
        let mut checked = Vec::with_capacity(writes.len());
        for (cell, regs) in &writes {
            let bytes =
                map::parameter_bytes(drive.store(), *cell, regs).map_err(|r| self.exception(r))?;
            drive
                .store()
                .check(cell.id, &bytes)
                .map_err(|r| self.exception(r))?;
            checked.push((cell.id, bytes));
        }
        for (id, bytes) in checked {
            drive.write(id, &bytes).map_err(|r| self.exception(r))?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lafert() -> Drive {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../descriptions/lafert-smartris"
        );
        Drive::new(drivegen::check(std::path::Path::new(path)).device.unwrap())
    }

    fn answer(request: &[u8]) -> Vec<u8> {
        let mut drive = lafert();
        let server = ModbusServer::new(drive.store().device(), None);
        let mut out = [0u8; pdu::MAX_PDU];
        let len = server.handle(&mut drive, request, &mut out);
        out[..len].to_vec()
    }

    #[test]
    fn the_manuals_status_read_is_answered() {
        // Input 0x0060 (drive status) after power-on: STANDBY.
        assert_eq!(
            answer(&[0x04, 0x00, 0x60, 0x00, 0x01]),
            [0x04, 0x02, 0x00, 0x02]
        );
    }

    #[test]
    fn malformed_and_unknown_requests_get_exceptions() {
        assert_eq!(answer(&[0x03, 0x00, 0x01]), [0x83, 0x03], "truncated");
        assert_eq!(
            answer(&[0x03, 0x00, 0x01, 0x00, 0x00]),
            [0x83, 0x03],
            "zero count"
        );
        assert_eq!(
            answer(&[0x2B, 0x0E, 0x01, 0x00, 0x00]),
            [0xAB, 0x01],
            "FC 0x2B"
        );
        assert_eq!(
            answer(&[0x06, 0x00, 0x01, 0x00, 0x08]),
            [0x86, 0x03],
            "control word 8"
        );
    }
}
