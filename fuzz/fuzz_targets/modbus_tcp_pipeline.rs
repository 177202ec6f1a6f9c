//! The Modbus TCP pipeline (`modbus::pipeline::TcpPipeline`) fed an arbitrary byte stream as
//! the server's answers, read in chunks of a chosen size, under a run of register reads.
//!
//! Input: one byte, the chunk size (1 to 64, its low six bits plus one), one byte, the number
//! of registers each read asks for (1 to 125), then the stream. Never panics and never waits:
//! each read ends with its answer (filed by transaction id, whatever else the stream holds), a
//! refused answer, or the end of the stream (`Closed`), after which every read is `Closed`.
#![no_main]

use core::time::Duration;

use drivebus::asynch::{Alarm, Timer};
use drivebus::modbus::pipeline::TcpPipeline;
use drivebus::modbus::{AsyncRegisterBus, Table, UnitId};
use drivebus::BusError;
use fuzz::chunks::{now, Chunks};
use libfuzzer_sys::fuzz_target;

/// A timer that never fires: an in-memory stream ends every wait first.
struct Never;

impl Timer for Never {
    type Alarm = Never;

    fn alarm(&self) -> Never {
        Never
    }

    async fn sleep(&self, _: Duration) {
        core::future::pending::<()>().await;
    }
}

impl Alarm for Never {
    fn set(&mut self, _: Duration) {}

    fn poll_due(&mut self, _: &mut core::task::Context<'_>) -> core::task::Poll<()> {
        core::task::Poll::Pending
    }
}

fuzz_target!(|input: &[u8]| {
    let [chunk, count, stream @ ..] = input else {
        return;
    };
    let reader = Chunks {
        data: stream,
        chunk: usize::from(chunk & 0x3F) + 1,
    };
    let count = usize::from(*count % 125) + 1;
    // Requests go nowhere.
    let requests = Chunks {
        data: &[],
        chunk: 1,
    };
    let mut pipeline = TcpPipeline::new(reader, requests, Never, Duration::from_secs(1));
    let mut closed = false;
    for start in 0..8u16 {
        let mut out = [0u16; 125];
        let outcome =
            now(pipeline.read_registers(UnitId(1), Table::Holding, start, &mut out[..count]));
        if closed {
            assert_eq!(outcome, Err(BusError::Closed), "closed for good");
        }
        closed |= outcome == Err(BusError::Closed);
    }
    assert_eq!(pipeline.in_flight(), 0, "every read gave up its slot");
});
