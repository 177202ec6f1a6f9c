//! [`AsyncLink`], the async twin of [`Link`](crate::Link), and [`Async`], which marks a handle
//! as async.

use crate::error::BusError;
use crate::link::ReadRequest;
use crate::Protocol;

/// The address type of `L`'s protocol.
type AddressOf<L> = <<L as AsyncLink>::Protocol as Protocol>::Address;

/// A connection to one device over one protocol, moving values as little-endian bytes, awaited:
/// the async twin of [`Link`](crate::Link), with the same contract method by method.
///
/// Dropping a future of this trait mid-request must leave the link usable: the next request
/// finds the bus as if the dropped one had never been sent, or ended (an SDO abort, a late
/// Modbus TCP answer discarded by its transaction id, an RTU line resynchronised).
// The futures are not declared `Send`: an implementation's are when its bus is, and a generic
// bound would shut out single-threaded executors (embassy) for no gain.
#[allow(async_fn_in_trait)]
pub trait AsyncLink {
    /// The protocol, which selects the addresses parameters are reached at.
    type Protocol: Protocol;

    /// Reads the value at `address` into `out` as little-endian bytes; returns the length.
    async fn read(&mut self, address: &AddressOf<Self>, out: &mut [u8]) -> Result<usize, BusError>;

    /// Writes the little-endian bytes of a value to `address`.
    async fn write(&mut self, address: &AddressOf<Self>, data: &[u8]) -> Result<(), BusError>;

    /// How many bytes a value at `address` occupies on the wire; 0 if the address does not say.
    fn wire_bytes(&self, address: &AddressOf<Self>) -> usize;

    /// Reads several values; links override this to coalesce requests.
    async fn read_many(
        &mut self,
        requests: &mut [ReadRequest<'_, AddressOf<Self>>],
    ) -> Result<(), BusError> {
        for request in requests.iter_mut() {
            request.len = self.read(&request.address, request.buf).await?;
        }
        Ok(())
    }

    /// After [`read_many`](AsyncLink::read_many) failed: the request whose read failed, judged
    /// from what was read. This default reads in order, so it is the first request left unread.
    fn failed_request(&self, requests: &[ReadRequest<'_, AddressOf<Self>>]) -> Option<usize> {
        requests.iter().position(|request| request.len == 0)
    }
}

/// An [`AsyncLink`] as a generated handle holds it: `Smartris<Async<L>>` has the accessors of
/// `Smartris<L>`, returning futures.
///
/// The wrapper is what lets one accessor type have both a blocking `read` (for a
/// [`Link`](crate::Link)) and an async `read` (for an `Async<L>`): the two impls are disjoint
/// because no `Async<L>` is a `Link`. The blocking and async APIs can so live in one dependency
/// graph without a feature that switches one into the other.
#[derive(Debug)]
pub struct Async<L>(pub L);

impl<L> Async<L> {
    /// The link.
    pub fn get_mut(&mut self) -> &mut L {
        &mut self.0
    }

    /// Gives the link back.
    pub fn into_inner(self) -> L {
        self.0
    }
}
