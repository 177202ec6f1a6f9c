//! [`ModbusLink`]: a [`RegisterBus`] bound to one unit, as the [`Link`] generated handles use.

use crate::error::BusError;
use crate::link::{Link, ReadRequest};

use super::address::{
    le_to_registers, registers_to_le, ModbusAddress, ModbusLimits, Table, UnitId, MAX_VALUE_WORDS,
};
use super::pdu::MAX_READ_REGISTERS;
use super::planner::{check_item, next_read, PlannedRead};
use super::{Modbus, RegisterBus, RegisterRead};

/// A [`RegisterBus`] bound to one unit: the [`Link`] generated Modbus drive handles use.
///
/// `L` is the device's [`ModbusLimits`]: `'static` constants in a generated crate (the default,
/// so `ModbusLink<B>` is what handles name), a view of its own model in a tool that loads a
/// description at run time.
#[derive(Debug)]
pub struct ModbusLink<B, L = ModbusLimits<'static>> {
    bus: B,
    unit: UnitId,
    limits: L,
}

impl<'a, B> ModbusLink<B, ModbusLimits<'a>> {
    /// Binds `bus` (a [`RegisterBus`], or an async one) to `unit`, respecting the device's
    /// `limits`.
    pub fn new(bus: B, unit: UnitId, limits: ModbusLimits<'a>) -> Self {
        Self { bus, unit, limits }
    }
    /// The device limits this link respects.
    pub fn limits(&self) -> ModbusLimits<'a> {
        self.limits
    }
}

impl<B> ModbusLink<B, StaticLimits> {
    /// Binds async `bus` to `unit`, respecting the device's `limits` (a generated crate's
    /// `MODBUS_LIMITS`): the link a generated async handle holds.
    pub fn new_static(bus: B, unit: UnitId, limits: ModbusLimits<'static>) -> Self {
        Self {
            bus,
            unit,
            limits: StaticLimits(limits),
        }
    }

    /// The device limits this link respects.
    pub fn static_limits(&self) -> &ModbusLimits<'static> {
        &self.limits.0
    }
}

/// `'static` [`ModbusLimits`] in a type without a lifetime parameter: what the async link
/// holds. A lifetime in the link's type, even `'static`, keeps rustc from proving the async
/// API's futures `Send` ("implementation of `AsyncLink` is not general enough"), and
/// `tokio::spawn` would refuse them.
#[derive(Debug, Clone, Copy)]
pub struct StaticLimits(pub ModbusLimits<'static>);

/// The limits a [`ModbusLink`] holds, as it reads them.
pub trait LimitsSource {
    /// The limits.
    fn get(&self) -> &ModbusLimits<'_>;
}

impl LimitsSource for ModbusLimits<'_> {
    fn get(&self) -> &ModbusLimits<'_> {
        self
    }
}

impl LimitsSource for StaticLimits {
    fn get(&self) -> &ModbusLimits<'_> {
        &self.0
    }
}

impl<B, L: LimitsSource> ModbusLink<B, L> {
    /// The unit this link talks to.
    pub fn unit(&self) -> UnitId {
        self.unit
    }
    /// The underlying bus.
    pub fn bus_mut(&mut self) -> &mut B {
        &mut self.bus
    }
    /// Gives the bus back.
    pub fn into_bus(self) -> B {
        self.bus
    }

    /// How many registers a read of `address` fills: checked against the limits before the I/O.
    pub(crate) fn read_words(&self, address: &ModbusAddress) -> Result<usize, BusError> {
        check_item(self.limits.get(), address)?;
        Ok(address.words as usize)
    }

    /// How a write of `data` to `address` goes out, with its registers put in `registers`.
    pub(crate) fn write_plan(
        &self,
        address: &ModbusAddress,
        data: &[u8],
        registers: &mut [u16; MAX_VALUE_WORDS],
    ) -> Result<WritePlan, BusError> {
        if address.table != Table::Holding {
            return Err(BusError::Unsupported(
                "only holding registers can be written",
            ));
        }
        let words = value_words(address)?;
        if data.len() != words * 2 {
            return Err(BusError::Frame(
                "value length does not match its register count",
            ));
        }
        le_to_registers(data, address.word_order, &mut registers[..words]);
        let limits = self.limits.get();
        Ok(if words == 1 {
            WritePlan::Single
        } else if limits.write_multiple && words <= limits.max_write_registers as usize {
            WritePlan::Multiple(words)
        } else {
            // Without FC 0x10 the words go one by one, lowest address first; the device sees
            // the value torn for a moment, which the description's word order makes explicit.
            WritePlan::OneByOne(words)
        })
    }

    /// A request the device's limits refuse, else the unread request of the lowest address: the
    /// planner reads in (table, address) order, not in the order values were asked for.
    pub(crate) fn failed_in(&self, requests: &[ReadRequest<'_, ModbusAddress>]) -> Option<usize> {
        let refused = requests
            .iter()
            .position(|request| check_item(self.limits.get(), &request.address).is_err());
        let unread = (0..requests.len()).filter(|&i| requests[i].len == 0);
        refused.or_else(|| {
            unread.min_by_key(|&i| (requests[i].address.table, requests[i].address.address))
        })
    }
}

/// How a value's registers are written: one FC 0x06, one FC 0x10 of that many, or that many FC
/// 0x06 (a device without FC 0x10).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum WritePlan {
    /// One register, FC 0x06.
    Single,
    /// That many registers in one FC 0x10.
    Multiple(usize),
    /// That many registers, each with FC 0x06, lowest address first.
    OneByOne(usize),
}

/// The value's little-endian bytes in `out` from the registers read: after a read's I/O.
pub(crate) fn value_from(
    registers: &[u16],
    address: &ModbusAddress,
    out: &mut [u8],
) -> Result<usize, BusError> {
    let bytes = out
        .get_mut(..registers.len() * 2)
        .ok_or(BusError::Frame("value buffer too small"))?;
    registers_to_le(registers, address.word_order, bytes);
    Ok(registers.len() * 2)
}

fn value_words(address: &ModbusAddress) -> Result<usize, BusError> {
    let words = address.words as usize;
    if words == 0 || words > MAX_VALUE_WORDS {
        return Err(BusError::Unsupported("value wider than 32 registers"));
    }
    Ok(words)
}

impl<B: RegisterBus> Link for ModbusLink<B, ModbusLimits<'_>> {
    type Protocol = Modbus;

    fn read(&mut self, address: &ModbusAddress, out: &mut [u8]) -> Result<usize, BusError> {
        let mut registers = [0u16; MAX_VALUE_WORDS];
        let registers = &mut registers[..self.read_words(address)?];
        self.bus
            .read_registers(self.unit, address.table, address.address, registers)?;
        value_from(registers, address, out)
    }

    fn write(&mut self, address: &ModbusAddress, data: &[u8]) -> Result<(), BusError> {
        let mut registers = [0u16; MAX_VALUE_WORDS];
        let (unit, start) = (self.unit, address.address);
        match self.write_plan(address, data, &mut registers)? {
            WritePlan::Single => self.bus.write_register(unit, start, registers[0]),
            WritePlan::Multiple(n) => self.bus.write_registers(unit, start, &registers[..n]),
            WritePlan::OneByOne(n) => {
                for (i, word) in registers[..n].iter().enumerate() {
                    self.bus.write_register(unit, start + i as u16, *word)?;
                }
                Ok(())
            }
        }
    }

    fn wire_bytes(&self, address: &ModbusAddress) -> usize {
        address.words as usize * 2
    }

    fn failed_request(&self, requests: &[ReadRequest<'_, ModbusAddress>]) -> Option<usize> {
        self.failed_in(requests)
    }

    /// Reads the batch with the fewest requests the device's limits allow (see
    /// [`planner`](super::planner)), handed to the bus [`MAX_IN_FLIGHT`](super::MAX_IN_FLIGHT)
    /// reads at a time ([`RegisterBus::read_register_batch`]) so a client that pipelines sends
    /// them together. On an error, the values already read keep their `len`; the others have
    /// `len == 0`.
    fn read_many(
        &mut self,
        requests: &mut [ReadRequest<'_, ModbusAddress>],
    ) -> Result<(), BusError> {
        let mut rounds = Rounds::new(requests);
        let mut registers = [[0u16; MAX_READ_REGISTERS as usize]; MAX_BATCH];
        while let Some((mut reads, count)) = rounds.next(&self.limits, &mut registers)? {
            let outcome = self.bus.read_register_batch(self.unit, &mut reads[..count]);
            rounds.delivered(&reads[..count], outcome)?;
        }
        Ok(())
    }
}

/// A batch read as rounds of at most [`MAX_BATCH`] planned reads, each handed to the bus at
/// once: the I/O-free part of `read_many`, blocking or async.
pub(crate) struct Rounds<'r, 'b> {
    requests: &'r mut [ReadRequest<'b, ModbusAddress>],
    planned: [Option<PlannedRead>; MAX_BATCH],
}

/// One round's reads (the first `count` of them), over a batch's register buffers.
type Round<'g> = ([RegisterRead<'g>; MAX_BATCH], usize);

impl<'r, 'b> Rounds<'r, 'b> {
    /// The rounds of `requests`; every value starts unread.
    pub(crate) fn new(requests: &'r mut [ReadRequest<'b, ModbusAddress>]) -> Self {
        for request in requests.iter_mut() {
            request.len = 0;
        }
        Self {
            requests,
            planned: [None; MAX_BATCH],
        }
    }

    /// Plans the next round into `registers`: its reads, or `None` once every value is read.
    pub(crate) fn next<'g>(
        &mut self,
        limits: &ModbusLimits,
        registers: &'g mut [[u16; MAX_READ_REGISTERS as usize]; MAX_BATCH],
    ) -> Result<Option<Round<'g>>, BusError> {
        self.planned = [None; MAX_BATCH];
        let count = plan_batch(limits, self.requests, &mut self.planned)?;
        if count == 0 {
            return Ok(None);
        }
        let mut reads = registers
            .each_mut()
            .map(|out| RegisterRead::new(Table::Input, 0, out));
        for (read, plan) in reads.iter_mut().zip(self.planned.iter().flatten()) {
            read.table = plan.table;
            read.start = plan.start;
            read.out = &mut core::mem::take(&mut read.out)[..plan.count as usize];
        }
        Ok(Some((reads, count)))
    }

    /// Takes the values of the round's finished reads; on an error, leaves the values the round
    /// did not read unread and returns it.
    pub(crate) fn delivered(
        &mut self,
        reads: &[RegisterRead<'_>],
        mut outcome: Result<(), BusError>,
    ) -> Result<(), BusError> {
        for (read, plan) in reads.iter().zip(self.planned.iter().flatten()) {
            outcome = outcome.and(deliver(self.requests, plan, read));
        }
        if outcome.is_err() {
            for request in self.requests.iter_mut().filter(|r| r.len == PLANNED) {
                request.len = 0;
            }
        }
        outcome
    }
}

/// Reads handed to the bus at once by [`ModbusLink::read_many`]: as many as a pipelining client
/// keeps in flight, so that a larger window is never cut into round trips here.
pub(crate) const MAX_BATCH: usize = super::MAX_IN_FLIGHT;

/// Marks a value planned but not read yet; `len == 0` means "not planned", any other length
/// "read" — a value is never zero bytes long.
const PLANNED: usize = usize::MAX;

/// Plans up to [`MAX_BATCH`] reads for the values not read yet and marks the values they cover
/// [`PLANNED`]; returns how many reads it planned.
fn plan_batch(
    limits: &ModbusLimits,
    requests: &mut [ReadRequest<'_, ModbusAddress>],
    planned: &mut [Option<PlannedRead>; MAX_BATCH],
) -> Result<usize, BusError> {
    for (count, slot) in planned.iter_mut().enumerate() {
        let Some(read) = next_read(limits, requests.len(), |i| {
            (requests[i].address, requests[i].len != 0)
        })?
        else {
            return Ok(count);
        };
        for request in requests.iter_mut().filter(|r| r.len == 0) {
            if read.offset_of(&request.address).is_some() {
                request.len = PLANNED;
            }
        }
        *slot = Some(read);
    }
    Ok(MAX_BATCH)
}

/// Copies the values `plan` covers out of its finished `read`; values of a read that did not
/// finish stay [`PLANNED`].
fn deliver(
    requests: &mut [ReadRequest<'_, ModbusAddress>],
    plan: &PlannedRead,
    read: &RegisterRead<'_>,
) -> Result<(), BusError> {
    if !read.done {
        return Ok(());
    }
    for request in requests.iter_mut().filter(|r| r.len == PLANNED) {
        let Some(offset) = plan.offset_of(&request.address) else {
            continue;
        };
        let words = request.address.words as usize;
        let Some(bytes) = request.buf.get_mut(..words * 2) else {
            return Err(BusError::Frame("value buffer too small"));
        };
        registers_to_le(
            &read.out[offset..offset + words],
            request.address.word_order,
            bytes,
        );
        request.len = words * 2;
    }
    Ok(())
}

#[cfg(all(test, feature = "std"))]
mod tests {
    use super::*;
    use crate::modbus::WordOrder;
    use crate::testing::{MemoryBus, Request};

    fn input(address: u16, words: u16) -> ModbusAddress {
        ModbusAddress::input(address, words, WordOrder::LowFirst)
    }

    fn lafert_bus() -> MemoryBus {
        let mut bus = MemoryBus::new();
        for a in 0x60..=0x70 {
            bus.set_register(Table::Input, a, a);
        }
        bus.set_register(Table::Input, 0x6B, 0x5678)
            .set_register(Table::Input, 0x6C, 0x1234);
        bus
    }

    /// Reads `addresses` in one batch, two registers per request at most; the failed request.
    fn failed_batch(addresses: &[ModbusAddress]) -> Option<usize> {
        let two_at_a_time = ModbusLimits {
            max_read_registers: 2,
            ..ModbusLimits::SPEC
        };
        let mut link = ModbusLink::new(lafert_bus(), UnitId(1), two_at_a_time);
        let mut bufs = [[0u8; 8]; 2];
        let mut requests: std::vec::Vec<_> = addresses
            .iter()
            .zip(&mut bufs)
            .map(|(address, buf)| ReadRequest {
                address: *address,
                buf,
                len: 0,
            })
            .collect();
        assert!(link.read_many(&mut requests).is_err());
        link.failed_request(&requests)
    }

    #[test]
    fn a_failed_batch_names_the_request_that_failed() {
        assert_eq!(failed_batch(&[input(0x60, 1), input(0x71, 1)]), Some(1));
        // Reads go by address, not by the order values were asked for: the failing read of 0x50
        // leaves 0x60 unread too, yet 0x50 is named.
        assert_eq!(failed_batch(&[input(0x60, 1), input(0x50, 1)]), Some(1));
        // A value wider than a read is refused before any read: that value is named.
        assert_eq!(failed_batch(&[input(0x60, 1), input(0x61, 3)]), Some(1));
    }

    #[test]
    fn batch_read_uses_the_plan() {
        let mut link = ModbusLink::new(lafert_bus(), UnitId(1), ModbusLimits::SPEC);
        let mut bufs = [[0u8; 8]; 3];
        let [a, b, c] = &mut bufs;
        let mut requests = [
            ReadRequest {
                address: input(0x70, 1),
                buf: a,
                len: 99,
            },
            ReadRequest {
                address: input(0x6B, 2),
                buf: b,
                len: 0,
            },
            ReadRequest {
                address: input(0x60, 1),
                buf: c,
                len: 0,
            },
        ];
        link.read_many(&mut requests).unwrap();
        assert_eq!(requests.map(|r| r.len), [2, 4, 2]);
        assert_eq!(u16::from_le_bytes([bufs[0][0], bufs[0][1]]), 0x70);
        assert_eq!(
            u32::from_le_bytes(bufs[1][..4].try_into().unwrap()),
            0x1234_5678
        );
        assert_eq!(u16::from_le_bytes([bufs[2][0], bufs[2][1]]), 0x60);
        let bus = link.into_bus();
        assert_eq!(
            bus.log(),
            [Request::Read {
                table: Table::Input,
                start: 0x60,
                count: 17
            }]
        );
    }

    #[test]
    fn a_batch_fills_a_whole_pipelining_window() {
        let limits = ModbusLimits {
            max_read_registers: 1,
            ..ModbusLimits::SPEC
        };
        let mut bufs = [[0u8; 2]; 20];
        let mut requests: std::vec::Vec<_> = (0u16..)
            .zip(bufs.iter_mut())
            .map(|(a, buf)| ReadRequest {
                address: input(2 * a, 1),
                buf,
                len: 0,
            })
            .collect();
        let mut planned = [None; MAX_BATCH];
        let count = plan_batch(&limits, &mut requests, &mut planned).unwrap();
        assert_eq!(count, crate::modbus::MAX_IN_FLIGHT);
    }

    #[test]
    fn batch_read_respects_limits_and_reports_errors() {
        let limits = ModbusLimits {
            max_read_registers: 1,
            ..ModbusLimits::SPEC
        };
        let mut link = ModbusLink::new(lafert_bus(), UnitId(1), limits);
        let (mut a, mut b) = ([0u8; 2], [0u8; 2]);
        let mut requests = [
            ReadRequest {
                address: input(0x60, 1),
                buf: &mut a,
                len: 0,
            },
            ReadRequest {
                address: input(0x61, 1),
                buf: &mut b,
                len: 0,
            },
        ];
        link.read_many(&mut requests).unwrap();
        assert_eq!(link.bus_mut().log().len(), 2);

        let mut link = ModbusLink::new(lafert_bus(), UnitId(1), ModbusLimits::SPEC);
        let mut small = [0u8; 2];
        let mut requests = [ReadRequest {
            address: input(0x6B, 2),
            buf: &mut small,
            len: 0,
        }];
        assert_eq!(
            link.read_many(&mut requests),
            Err(BusError::Frame("value buffer too small"))
        );
        let mut buf = [0u8; 2];
        let mut requests = [ReadRequest {
            address: input(0x71, 1),
            buf: &mut buf,
            len: 0,
        }];
        assert_eq!(
            link.read_many(&mut requests),
            Err(BusError::ModbusException {
                function: 4,
                code: crate::modbus::ExceptionCode::IllegalDataAddress
            })
        );
        assert_eq!(requests[0].len, 0);
    }
}
