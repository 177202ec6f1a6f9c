//! Test doubles for tests and examples (feature `testing`).
//!
//! * [`MemoryBus`] — registers and objects in memory, answering Modbus, SDO and RS-232 requests
//!   as a device would; it records every request, so tests can count transactions.
//! * [`SdoRecorder`] — a [`MemoryBus`] that also keeps the first CAN frame of every SDO transfer.
//! * `RtuRecorder` (with `modbus-core`) — a [`MemoryBus`] that also keeps every request as its RTU
//!   frame.
//! * [`Recorded`] — any link, blocking or async, keeping every request it passes on.

mod recorded;

pub use recorded::{LinkRequest, Recorded};

use std::collections::BTreeMap;
use std::vec::Vec;

use crate::canopen::{NodeId, SdoBus};
use crate::error::BusError;
use crate::modbus::{RegisterBus, Table, UnitId};
use crate::rs232::data::{Answer, Request as Rs232Request, Value};
use crate::rs232::{Rs232Error, StationId, TelegramBus};

/// One request as the memory bus saw it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Request {
    /// A register read.
    Read {
        /// Table read.
        table: Table,
        /// First register.
        start: u16,
        /// Register count.
        count: u16,
    },
    /// A register write (single or multiple).
    Write {
        /// First register.
        start: u16,
        /// Values written.
        values: Vec<u16>,
    },
    /// An SDO (or RS-232) upload.
    Upload(u16, u8),
    /// An SDO (or RS-232) download.
    Download(u16, u8, Vec<u8>),
}

/// Registers and objects held in memory. Unknown addresses answer like a device would: Modbus
/// exception 0x02 (illegal data address) or SDO abort 0x06020000 (object does not exist).
#[derive(Debug, Default, Clone)]
pub struct MemoryBus {
    registers: BTreeMap<(Table, u16), u16>,
    objects: BTreeMap<(u16, u8), Vec<u8>>,
    log: Vec<Request>,
}

impl MemoryBus {
    /// An empty bus.
    pub fn new() -> Self {
        Self::default()
    }

    /// Sets a register.
    pub fn set_register(&mut self, table: Table, address: u16, value: u16) -> &mut Self {
        self.registers.insert((table, address), value);
        self
    }

    /// A register's value.
    pub fn register(&self, table: Table, address: u16) -> Option<u16> {
        self.registers.get(&(table, address)).copied()
    }

    /// Sets an object's value bytes.
    pub fn set_object(&mut self, index: u16, subindex: u8, value: &[u8]) -> &mut Self {
        self.objects.insert((index, subindex), value.to_vec());
        self
    }

    /// An object's value bytes.
    pub fn object(&self, index: u16, subindex: u8) -> Option<&[u8]> {
        self.objects.get(&(index, subindex)).map(Vec::as_slice)
    }

    /// Every request seen so far.
    pub fn log(&self) -> &[Request] {
        &self.log
    }

    fn exception(function: u8) -> BusError {
        BusError::ModbusException {
            function,
            code: crate::modbus::ExceptionCode::IllegalDataAddress,
        }
    }
}

impl RegisterBus for MemoryBus {
    fn read_registers(
        &mut self,
        _unit: UnitId,
        table: Table,
        start: u16,
        out: &mut [u16],
    ) -> Result<(), BusError> {
        self.log.push(Request::Read {
            table,
            start,
            count: out.len() as u16,
        });
        let function = if table == Table::Input { 0x04 } else { 0x03 };
        for (offset, slot) in out.iter_mut().enumerate() {
            let address = start
                .checked_add(offset as u16)
                .ok_or(Self::exception(function))?;
            *slot = self
                .register(table, address)
                .ok_or(Self::exception(function))?;
        }
        Ok(())
    }

    fn write_register(&mut self, unit: UnitId, address: u16, value: u16) -> Result<(), BusError> {
        self.write_registers(unit, address, &[value])
    }

    fn write_registers(
        &mut self,
        _unit: UnitId,
        start: u16,
        values: &[u16],
    ) -> Result<(), BusError> {
        self.log.push(Request::Write {
            start,
            values: values.to_vec(),
        });
        let function = if values.len() == 1 { 0x06 } else { 0x10 };
        // Check every address first so a refused write changes nothing.
        for offset in 0..values.len() as u16 {
            let address = start.checked_add(offset).ok_or(Self::exception(function))?;
            self.register(Table::Holding, address)
                .ok_or(Self::exception(function))?;
        }
        for (offset, value) in values.iter().enumerate() {
            self.registers
                .insert((Table::Holding, start + offset as u16), *value);
        }
        Ok(())
    }
}

impl SdoBus for MemoryBus {
    fn upload(
        &mut self,
        _node: NodeId,
        index: u16,
        subindex: u8,
        out: &mut [u8],
    ) -> Result<usize, BusError> {
        self.log.push(Request::Upload(index, subindex));
        let value = self.object(index, subindex).ok_or(BusError::SdoAbort {
            index,
            subindex,
            code: crate::canopen::sdo::AbortCode::ObjectDoesNotExist,
        })?;
        let target = out
            .get_mut(..value.len())
            .ok_or(BusError::Frame("object larger than buffer"))?;
        target.copy_from_slice(value);
        Ok(value.len())
    }

    fn download(
        &mut self,
        _node: NodeId,
        index: u16,
        subindex: u8,
        data: &[u8],
    ) -> Result<(), BusError> {
        self.log
            .push(Request::Download(index, subindex, data.to_vec()));
        let slot = self
            .objects
            .get_mut(&(index, subindex))
            .ok_or(BusError::SdoAbort {
                index,
                subindex,
                code: crate::canopen::sdo::AbortCode::ObjectDoesNotExist,
            })?;
        *slot = data.to_vec();
        Ok(())
    }
}

/// The same objects over the Kinco RS-232 data protocol; unknown objects get an error answer
/// with cause 0x06020000.
impl TelegramBus for MemoryBus {
    fn exchange(
        &mut self,
        _station: StationId,
        request: &Rs232Request,
    ) -> Result<Answer, BusError> {
        let object = request.object();
        let refused = Rs232Error::Refused {
            cause: crate::canopen::sdo::AbortCode::ObjectDoesNotExist.code(),
        }
        .about(object);
        match request {
            Rs232Request::Upload(_) => {
                self.log
                    .push(Request::Upload(object.index, object.subindex));
                let value = self.object(object.index, object.subindex).ok_or(refused)?;
                let value = Value::new(value).map_err(|error| error.about(object))?;
                Ok(Answer::Uploaded(object, value))
            }
            Rs232Request::Download(_, value) => {
                let data = value.as_bytes().to_vec();
                self.log.push(Request::Download(
                    object.index,
                    object.subindex,
                    data.clone(),
                ));
                let slot = self
                    .objects
                    .get_mut(&(object.index, object.subindex))
                    .ok_or(refused)?;
                *slot = data;
                Ok(Answer::Downloaded(object))
            }
        }
    }
}

/// A [`MemoryBus`] that also keeps the first CAN frame of every SDO transfer asked of it, as the
/// sans-I/O SDO client would send it: tests compare those frames with a manual's printed bytes.
#[derive(Debug, Default)]
pub struct SdoRecorder {
    /// Where the objects live.
    pub memory: MemoryBus,
    /// The request frames, oldest first.
    pub frames: Vec<crate::canopen::CanFrame>,
}

impl SdoRecorder {
    fn client(node: NodeId) -> crate::canopen::sdo::client::SdoClient {
        crate::canopen::sdo::client::SdoClient::new(node, core::time::Duration::from_secs(1))
    }
}

impl SdoBus for SdoRecorder {
    fn upload(
        &mut self,
        node: NodeId,
        index: u16,
        subindex: u8,
        out: &mut [u8],
    ) -> Result<usize, BusError> {
        use crate::canopen::sdo::Transfer;
        let mut scratch = [0u8; 8];
        let mut transfer =
            Self::client(node).upload(index, subindex, &mut scratch, core::time::Duration::ZERO);
        self.frames.extend(transfer.poll_transmit());
        self.memory.upload(node, index, subindex, out)
    }

    fn download(
        &mut self,
        node: NodeId,
        index: u16,
        subindex: u8,
        data: &[u8],
    ) -> Result<(), BusError> {
        use crate::canopen::sdo::Transfer;
        let mut transfer =
            Self::client(node).download(index, subindex, data, core::time::Duration::ZERO);
        self.frames.extend(transfer.poll_transmit());
        self.memory.download(node, index, subindex, data)
    }
}

/// A [`MemoryBus`] that also keeps every request as the RTU frame (unit, PDU, CRC)
/// [`encode_request`](crate::modbus::rtu::encode_request) builds for it: what would go on the
/// RS-485 wire, for tests against a manual's printed frames.
#[cfg(feature = "modbus-core")]
#[derive(Debug, Default)]
pub struct RtuRecorder {
    /// Where the registers live.
    pub memory: MemoryBus,
    /// The request frames, oldest first.
    pub frames: Vec<Vec<u8>>,
}

#[cfg(feature = "modbus-core")]
impl RtuRecorder {
    fn record(
        &mut self,
        unit: UnitId,
        request: &crate::modbus::pdu::Request<'_>,
    ) -> Result<(), BusError> {
        use crate::modbus::rtu::{encode_request, MAX_ADU};
        let mut frame = [0u8; MAX_ADU];
        let len = encode_request(unit, request, &mut frame)?;
        self.frames.push(frame[..len].to_vec());
        Ok(())
    }
}

#[cfg(feature = "modbus-core")]
impl RegisterBus for RtuRecorder {
    fn read_registers(
        &mut self,
        unit: UnitId,
        table: Table,
        start: u16,
        out: &mut [u16],
    ) -> Result<(), BusError> {
        use crate::modbus::pdu::Request;
        let count = out.len() as u16;
        let request = match table {
            Table::Input => Request::ReadInputRegisters { start, count },
            Table::Holding => Request::ReadHoldingRegisters { start, count },
        };
        self.record(unit, &request)?;
        self.memory.read_registers(unit, table, start, out)
    }

    fn write_register(&mut self, unit: UnitId, address: u16, value: u16) -> Result<(), BusError> {
        let request = crate::modbus::pdu::Request::WriteSingleRegister { address, value };
        self.record(unit, &request)?;
        self.memory.write_register(unit, address, value)
    }

    fn write_registers(
        &mut self,
        unit: UnitId,
        start: u16,
        values: &[u16],
    ) -> Result<(), BusError> {
        let request = crate::modbus::pdu::Request::write_registers(start, values);
        self.record(unit, &request)?;
        self.memory.write_registers(unit, start, values)
    }
}

#[cfg(feature = "async")]
pub use immediate::{now, Immediate};

/// An async link over a blocking one, for testing the async API without an executor.
#[cfg(feature = "async")]
mod immediate {
    use core::future::Future;
    use core::pin::pin;
    use core::task::{Context, Poll, Waker};

    use crate::asynch::AsyncLink;
    use crate::error::BusError;
    use crate::link::{Link, ReadRequest};
    use crate::Protocol;

    /// An [`AsyncLink`] whose futures complete at their first poll, over the blocking link `L`
    /// (a link over a [`MemoryBus`](super::MemoryBus)): the typed async API tested against the
    /// very state the blocking one is, polled by [`now`]. Not a transport: it blocks in `poll`.
    #[derive(Debug)]
    pub struct Immediate<L>(pub L);

    impl<L: Link> AsyncLink for Immediate<L> {
        type Protocol = L::Protocol;

        async fn read(
            &mut self,
            address: &<L::Protocol as Protocol>::Address,
            out: &mut [u8],
        ) -> Result<usize, BusError> {
            self.0.read(address, out)
        }

        async fn write(
            &mut self,
            address: &<L::Protocol as Protocol>::Address,
            data: &[u8],
        ) -> Result<(), BusError> {
            self.0.write(address, data)
        }

        fn wire_bytes(&self, address: &<L::Protocol as Protocol>::Address) -> usize {
            self.0.wire_bytes(address)
        }

        async fn read_many(
            &mut self,
            requests: &mut [ReadRequest<'_, <L::Protocol as Protocol>::Address>],
        ) -> Result<(), BusError> {
            self.0.read_many(requests)
        }

        fn failed_request(
            &self,
            requests: &[ReadRequest<'_, <L::Protocol as Protocol>::Address>],
        ) -> Option<usize> {
            self.0.failed_request(requests)
        }
    }

    /// An SDO client whose futures complete at their first poll, over the blocking one `B`
    /// (a [`MemoryBus`](super::MemoryBus), an [`SdoRecorder`](super::SdoRecorder)).
    #[cfg(feature = "canopen")]
    impl<B: crate::canopen::SdoBus> crate::canopen::AsyncSdoBus for Immediate<B> {
        async fn upload(
            &mut self,
            node: crate::canopen::NodeId,
            index: u16,
            subindex: u8,
            out: &mut [u8],
        ) -> Result<usize, BusError> {
            self.0.upload(node, index, subindex, out)
        }

        async fn download(
            &mut self,
            node: crate::canopen::NodeId,
            index: u16,
            subindex: u8,
            data: &[u8],
        ) -> Result<(), BusError> {
            self.0.download(node, index, subindex, data)
        }
    }

    /// Polls `future` once: its output if it completed, `None` if it waits on something.
    pub fn now<F: Future>(future: F) -> Option<F::Output> {
        let mut cx = Context::from_waker(Waker::noop());
        match pin!(future).poll(&mut cx) {
            Poll::Ready(output) => Some(output),
            Poll::Pending => None,
        }
    }
}
