//! An in-memory byte stream for the async targets: what an adapter, a relay or a server sends,
//! handed out in chunks of a chosen size (as the transport splits it); writes go nowhere. And
//! [`now`], which polls a future once: an in-memory stream never makes anything wait.

use core::convert::Infallible;
use core::future::Future;
use core::pin::pin;
use core::task::{Context, Poll, Waker};

/// The fuzzer's bytes, at most `chunk` of them per read.
pub struct Chunks<'a> {
    /// What is left to read.
    pub data: &'a [u8],
    /// Most bytes one read returns.
    pub chunk: usize,
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

/// Polls `future` once; panics if it waits, which nothing over an in-memory stream may.
pub fn now<F: Future>(future: F) -> F::Output {
    match pin!(future).poll(&mut Context::from_waker(Waker::noop())) {
        Poll::Ready(output) => output,
        Poll::Pending => panic!("a future waited on an in-memory stream"),
    }
}
