//! The [`BusError`] of a failed `embedded-io-async` read or write.

use crate::error::BusError;

/// The runtime error for an I/O error of an async byte stream: its kind, as `std::io` names it
/// (without `std`, a frame error saying the stream failed).
pub(crate) fn bus_error<E: embedded_io_async::Error>(error: &E) -> BusError {
    #[cfg(feature = "std")]
    {
        use embedded_io_async::ErrorKind as E;
        use std::io::ErrorKind as S;
        BusError::Io(match error.kind() {
            E::NotFound => S::NotFound,
            E::PermissionDenied => S::PermissionDenied,
            E::ConnectionRefused => S::ConnectionRefused,
            E::ConnectionReset => S::ConnectionReset,
            E::ConnectionAborted => S::ConnectionAborted,
            E::NotConnected => S::NotConnected,
            E::BrokenPipe => S::BrokenPipe,
            E::TimedOut => S::TimedOut,
            E::Interrupted => S::Interrupted,
            E::WriteZero => S::WriteZero,
            E::InvalidInput => S::InvalidInput,
            E::InvalidData => S::InvalidData,
            E::OutOfMemory => S::OutOfMemory,
            _ => S::Other,
        })
    }
    #[cfg(not(feature = "std"))]
    {
        let _ = error;
        BusError::Frame("the byte stream failed")
    }
}

/// The end of an async byte stream (a read of 0 bytes): the peer closed it.
pub(crate) fn closed() -> BusError {
    #[cfg(feature = "std")]
    {
        BusError::Io(std::io::ErrorKind::UnexpectedEof)
    }
    #[cfg(not(feature = "std"))]
    {
        BusError::Frame("the byte stream was closed")
    }
}
