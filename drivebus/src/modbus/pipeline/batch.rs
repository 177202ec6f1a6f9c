//! One handle's batch of reads (a planned `read_many`) on the pipeline: its requests sent one
//! after the other without waiting, up to [`MAX_IN_FLIGHT`] at a time, then their answers taken
//! in order. Answers are filed by transaction id whoever reads them, so waiting for the first
//! also files the others as they come.

use embedded_io_async::{Read, Write};

use super::{Shared, SlotGuard, TcpPipeline};
use crate::asynch::{within_alarm, Timer};
use crate::error::BusError;
use crate::modbus::async_client::count;
use crate::modbus::pdu::{decode_registers, Request, MAX_PDU};
use crate::modbus::tcp::{encode_request, MAX_ADU};
use crate::modbus::{RegisterRead, UnitId, MAX_IN_FLIGHT};

impl<R: Read, W: Write, T: Timer> TcpPipeline<R, W, T> {
    /// Reads the reads not done yet, [`MAX_IN_FLIGHT`] in flight at a time, marking each done
    /// once its registers are in; each window must complete within the timeout.
    pub(super) async fn read_batch(
        &mut self,
        unit: UnitId,
        reads: &mut [RegisterRead<'_>],
    ) -> Result<(), BusError> {
        let shared = &*self.shared;
        for window in reads.chunks_mut(MAX_IN_FLIGHT) {
            within_alarm(
                &mut self.alarm,
                shared.timeout,
                shared.read_window(unit, window),
            )
            .await
            .map_err(|_| BusError::Timeout)??;
        }
        Ok(())
    }
}

impl<R: Read, W: Write, T> Shared<R, W, T> {
    /// Sends every read of `reads` not done yet, then takes their answers in order.
    async fn read_window(
        &self,
        unit: UnitId,
        reads: &mut [RegisterRead<'_>],
    ) -> Result<(), BusError> {
        // A request's slot lives until its answer is taken, or the window ends.
        let mut slots: [Option<SlotGuard<'_, R, W, T>>; MAX_IN_FLIGHT] =
            core::array::from_fn(|_| None);
        for (read, slot) in reads.iter().zip(slots.iter_mut()) {
            if read.done {
                continue;
            }
            let request = Request::read_registers(read.table, read.start, count(read.out.len())?);
            request.validate()?;
            let transaction = self.lock().open_slot(unit)?;
            let guard = slot.insert(SlotGuard {
                pipeline: self,
                transaction,
            });
            let mut frame = [0u8; MAX_ADU];
            let len = encode_request(transaction, unit, &request, &mut frame)?;
            self.send(guard.transaction, &frame[..len]).await?;
        }
        for (read, slot) in reads.iter_mut().zip(slots.iter_mut()) {
            let Some(guard) = slot.take() else {
                continue;
            };
            let mut pdu = [0u8; MAX_PDU];
            let len = self.await_answer(guard.transaction, &mut pdu).await?;
            let request = Request::read_registers(read.table, read.start, count(read.out.len())?);
            decode_registers(&request, &pdu[..len], read.out)?;
            read.done = true;
        }
        Ok(())
    }
}
