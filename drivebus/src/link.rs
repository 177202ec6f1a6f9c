//! The one trait a protocol binding implements for generated drive handles.

use crate::error::BusError;
use crate::Protocol;

pub use drivebus_model::MAX_VALUE_BYTES;

/// One value to fetch in a batch read: where it lives, and where its bytes go.
#[derive(Debug)]
pub struct ReadRequest<'b, A> {
    /// Protocol address of the value.
    pub address: A,
    /// Destination for the value's little-endian bytes.
    pub buf: &'b mut [u8],
    /// Set by the link: how many bytes of `buf` hold the value.
    pub len: usize,
}

/// A connection to one device over one protocol, moving values as little-endian bytes.
pub trait Link {
    /// The protocol, which selects the addresses parameters are reached at.
    type Protocol: Protocol;

    /// Reads the value at `address` into `out` as little-endian bytes; returns the length.
    fn read(
        &mut self,
        address: &<Self::Protocol as Protocol>::Address,
        out: &mut [u8],
    ) -> Result<usize, BusError>;

    /// Writes the little-endian bytes of a value to `address`.
    fn write(
        &mut self,
        address: &<Self::Protocol as Protocol>::Address,
        data: &[u8],
    ) -> Result<(), BusError>;

    /// How many bytes a value at `address` occupies on the wire; 0 if the address does not say.
    fn wire_bytes(&self, address: &<Self::Protocol as Protocol>::Address) -> usize;

    /// Reads several values; links override this to coalesce requests.
    fn read_many(
        &mut self,
        requests: &mut [ReadRequest<'_, <Self::Protocol as Protocol>::Address>],
    ) -> Result<(), BusError> {
        for request in requests.iter_mut() {
            request.len = self.read(&request.address, request.buf)?;
        }
        Ok(())
    }

    /// After [`read_many`](Link::read_many) failed: the request whose read failed, judged from
    /// what was read. This default reads in order, so it is the first request left unread.
    fn failed_request(
        &self,
        requests: &[ReadRequest<'_, <Self::Protocol as Protocol>::Address>],
    ) -> Option<usize> {
        requests.iter().position(|request| request.len == 0)
    }
}
