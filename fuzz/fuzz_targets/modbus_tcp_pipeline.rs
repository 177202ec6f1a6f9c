//! The Modbus TCP pipeline (`modbus::pipeline::TcpPipeline`) fed an arbitrary byte stream as
//! the server's answers, read in chunks of a chosen size, under a run of register reads.
//!
//! Input: one byte, the chunk size (1 to 64, its low six bits plus one), one byte, the number
//! of registers each read asks for (1 to 125), then the stream. Never panics and never waits:
//! each read ends with its answer (filed by transaction id, whatever else the stream holds), a
//! refused answer, or the end of the stream (`Closed`), after which every read is `Closed`.
#![no_main]

use core::convert::Infallible;
use core::future::Future;
use core::pin::pin;
use core::task::{Context, Poll, Waker};
use core::time::Duration;

use drivebus::asynch::Timer;
use drivebus::modbus::pipeline::TcpPipeline;
use drivebus::modbus::{AsyncRegisterBus, Table, UnitId};
use drivebus::BusError;
use libfuzzer_sys::fuzz_target;

/// The server's side in memory: at most `chunk` bytes per read.
struct Chunks<'a> {
    data: &'a [u8],
    chunk: usize,
}

impl embedded_io_async::ErrorType for Chunks<'_> {
    type Error = Infallible;
}

impl embedded_io_async::Read for Chunks<'_> {
    async fn read(&mut self, buf: &mut [u8]) -> Result<usize, Infallible> {
        let n = self.chunk.min(buf.len()).min(self.data.len());
        buf[..n].copy_from_slice(&self.data[..n]);
        self.data = &self.data[n..];
        Ok(n)
    }
}

/// Requests go nowhere.
struct Sink;

impl embedded_io_async::ErrorType for Sink {
    type Error = Infallible;
}

impl embedded_io_async::Write for Sink {
    async fn write(&mut self, buf: &[u8]) -> Result<usize, Infallible> {
        Ok(buf.len())
    }

    async fn flush(&mut self) -> Result<(), Infallible> {
        Ok(())
    }
}

/// A timer that never fires: an in-memory stream ends every wait first.
struct Never;

impl Timer for Never {
    async fn sleep(&self, _: Duration) {
        core::future::pending::<()>().await;
    }
}

/// Polls once: nothing here may wait.
fn now<F: Future>(future: F) -> F::Output {
    match pin!(future).poll(&mut Context::from_waker(Waker::noop())) {
        Poll::Ready(output) => output,
        Poll::Pending => panic!("a read waited on an in-memory stream"),
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
    let mut pipeline = TcpPipeline::new(reader, Sink, Never, Duration::from_secs(1));
    let mut closed = false;
    for start in 0..8u16 {
        let mut out = [0u16; 125];
        let outcome = now(pipeline.read_registers(UnitId(1), Table::Holding, start, &mut out[..count]));
        if closed {
            assert_eq!(outcome, Err(BusError::Closed), "closed for good");
        }
        closed |= outcome == Err(BusError::Closed);
    }
    assert_eq!(pipeline.in_flight(), 0, "every read gave up its slot");
});
