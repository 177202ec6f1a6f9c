//! The async SLCAN and candump buses fed an arbitrary byte stream, read in chunks of a chosen
//! size (what an adapter or a relay sends, split as the transport splits it).
//!
//! Input: one byte, the chunk size (1 to 64, from the byte's low six bits plus one), then the
//! stream. The same stream goes to both buses. Never panics and never waits: every receive
//! ends in a frame, a report or the end of the stream, and each consumes input, so both buses
//! reach the end (`UnexpectedEof`) within as many receives as there are bytes.
#![no_main]

use core::convert::Infallible;
use core::future::Future;
use core::pin::pin;
use core::task::{Context, Poll, Waker};

use drivebus::canopen::can::async_candump::AsyncCandumpBus;
use drivebus::canopen::can::async_slcan::AsyncSlcanBus;
use drivebus::canopen::can::AsyncCanBus;
use drivebus::BusError;
use libfuzzer_sys::fuzz_target;

/// An in-memory stream handing out at most `chunk` bytes per read; writes go nowhere.
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

impl embedded_io_async::Write for Chunks<'_> {
    async fn write(&mut self, buf: &[u8]) -> Result<usize, Infallible> {
        Ok(buf.len())
    }

    async fn flush(&mut self) -> Result<(), Infallible> {
        Ok(())
    }
}

/// Polls once: an in-memory stream never makes a receive wait.
fn now<F: Future>(future: F) -> F::Output {
    match pin!(future).poll(&mut Context::from_waker(Waker::noop())) {
        Poll::Ready(output) => output,
        Poll::Pending => panic!("a receive waited on an in-memory stream"),
    }
}

/// Receives until the end of the stream, which must come within `bound` receives.
fn drain(bound: usize, mut receive: impl FnMut() -> Result<(), BusError>) {
    for _ in 0..=bound {
        match receive() {
            Ok(()) => {}
            Err(BusError::Io(std::io::ErrorKind::UnexpectedEof)) => return,
            Err(other) => panic!("only the end of the stream ends it: {other:?}"),
        }
    }
    panic!("more than {bound} receives without reaching the end");
}

fuzz_target!(|input: &[u8]| {
    let Some((&size, stream)) = input.split_first() else {
        return;
    };
    let chunk = usize::from(size & 0x3F) + 1;
    let mut slcan = AsyncSlcanBus::new(Chunks {
        data: stream,
        chunk,
    });
    drain(stream.len(), || now(slcan.recv_event()).map(drop));
    let mut candump = AsyncCandumpBus::new(
        Chunks {
            data: stream,
            chunk,
        },
        Chunks { data: &[], chunk },
    );
    drain(stream.len(), || now(candump.recv()).map(drop));
});
