//! [`Recorded`]: a link that keeps every request it passes on, blocking or awaited, so a test
//! can compare what the blocking and the async API sent for the same procedure.

use std::vec::Vec;

use crate::error::BusError;
use crate::link::{Link, ReadRequest};
use crate::Protocol;

/// One request a [`Recorded`] link passed on.
#[derive(Debug, Clone, PartialEq)]
pub enum LinkRequest<A> {
    /// A read of the value at the address.
    Read(A),
    /// A write of these little-endian bytes to the address.
    Write(A, Vec<u8>),
}

/// A link (blocking [`Link`] or, with feature `async`, [`AsyncLink`](crate::asynch::AsyncLink))
/// that passes every request on to `L` and keeps it, in order, whether it succeeded or not.
#[derive(Debug)]
pub struct Recorded<L, A> {
    link: L,
    log: Vec<LinkRequest<A>>,
}

impl<L, A> Recorded<L, A> {
    /// Records the requests passed on to `link`.
    pub fn new(link: L) -> Self {
        Self {
            link,
            log: Vec::new(),
        }
    }

    /// The requests passed on so far, oldest first.
    pub fn log(&self) -> &[LinkRequest<A>] {
        &self.log
    }

    /// The log with each run of identical requests kept once: a status polled more often while
    /// one drive took its time is one poll, so two runs of one procedure compare equal when they
    /// sent the same requests in the same order.
    pub fn log_without_repeats(&self) -> Vec<LinkRequest<A>>
    where
        A: Clone + PartialEq,
    {
        let mut log = self.log.clone();
        log.dedup();
        log
    }

    /// The recorded link.
    pub fn get_mut(&mut self) -> &mut L {
        &mut self.link
    }

    fn reads<'a>(&mut self, requests: impl Iterator<Item = &'a A>)
    where
        A: Copy + 'a,
    {
        self.log.extend(requests.copied().map(LinkRequest::Read));
    }
}

/// The address type of `L`'s protocol.
type AddressOf<L> = <<L as Link>::Protocol as Protocol>::Address;

impl<L: Link> Link for Recorded<L, AddressOf<L>> {
    type Protocol = L::Protocol;

    fn read(&mut self, address: &AddressOf<L>, out: &mut [u8]) -> Result<usize, BusError> {
        self.log.push(LinkRequest::Read(*address));
        self.link.read(address, out)
    }

    fn write(&mut self, address: &AddressOf<L>, data: &[u8]) -> Result<(), BusError> {
        self.log.push(LinkRequest::Write(*address, data.to_vec()));
        self.link.write(address, data)
    }

    fn wire_bytes(&self, address: &AddressOf<L>) -> usize {
        self.link.wire_bytes(address)
    }

    fn read_many(
        &mut self,
        requests: &mut [ReadRequest<'_, AddressOf<L>>],
    ) -> Result<(), BusError> {
        self.reads(requests.iter().map(|r| &r.address));
        self.link.read_many(requests)
    }

    fn failed_request(&self, requests: &[ReadRequest<'_, AddressOf<L>>]) -> Option<usize> {
        self.link.failed_request(requests)
    }
}

#[cfg(feature = "async")]
mod awaited {
    use super::{LinkRequest, Recorded};
    use crate::asynch::AsyncLink;
    use crate::error::BusError;
    use crate::link::ReadRequest;
    use crate::Protocol;

    /// The address type of `L`'s protocol.
    type AddressOf<L> = <<L as AsyncLink>::Protocol as Protocol>::Address;

    impl<L: AsyncLink> AsyncLink for Recorded<L, AddressOf<L>> {
        type Protocol = L::Protocol;

        async fn read(
            &mut self,
            address: &AddressOf<L>,
            out: &mut [u8],
        ) -> Result<usize, BusError> {
            self.log.push(LinkRequest::Read(*address));
            self.link.read(address, out).await
        }

        async fn write(&mut self, address: &AddressOf<L>, data: &[u8]) -> Result<(), BusError> {
            self.log.push(LinkRequest::Write(*address, data.to_vec()));
            self.link.write(address, data).await
        }

        fn wire_bytes(&self, address: &AddressOf<L>) -> usize {
            self.link.wire_bytes(address)
        }

        async fn read_many(
            &mut self,
            requests: &mut [ReadRequest<'_, AddressOf<L>>],
        ) -> Result<(), BusError> {
            self.reads(requests.iter().map(|r| &r.address));
            self.link.read_many(requests).await
        }

        fn failed_request(&self, requests: &[ReadRequest<'_, AddressOf<L>>]) -> Option<usize> {
            self.link.failed_request(requests)
        }
    }
}
