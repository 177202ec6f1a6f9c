//! The SDO-bus trait CANopen transports implement, and the [`Link`] generated drive handles use.

use super::address::{CanOpen, NodeId, ObjectAddress};
use crate::error::BusError;
use crate::link::Link;

/// A CANopen client able to upload and download object values of one node at a time.
pub trait SdoBus {
    /// Reads the value of `index:subindex` into `out`, returning its length.
    fn upload(
        &mut self,
        node: NodeId,
        index: u16,
        subindex: u8,
        out: &mut [u8],
    ) -> Result<usize, BusError>;
    /// Writes `data` to `index:subindex`.
    fn download(
        &mut self,
        node: NodeId,
        index: u16,
        subindex: u8,
        data: &[u8],
    ) -> Result<(), BusError>;
}

impl<B: SdoBus + ?Sized> SdoBus for &mut B {
    fn upload(
        &mut self,
        node: NodeId,
        index: u16,
        subindex: u8,
        out: &mut [u8],
    ) -> Result<usize, BusError> {
        (**self).upload(node, index, subindex, out)
    }
    fn download(
        &mut self,
        node: NodeId,
        index: u16,
        subindex: u8,
        data: &[u8],
    ) -> Result<(), BusError> {
        (**self).download(node, index, subindex, data)
    }
}

/// A CANopen client able to upload and download object values of one node at a time,
/// awaited: the async twin of [`SdoBus`], with the same contract. Dropping a future mid-transfer
/// ends the transfer with an SDO abort.
#[cfg(feature = "async")]
#[allow(async_fn_in_trait)]
pub trait AsyncSdoBus {
    /// Reads the value of `index:subindex` into `out`, returning its length.
    async fn upload(
        &mut self,
        node: NodeId,
        index: u16,
        subindex: u8,
        out: &mut [u8],
    ) -> Result<usize, BusError>;
    /// Writes `data` to `index:subindex`.
    async fn download(
        &mut self,
        node: NodeId,
        index: u16,
        subindex: u8,
        data: &[u8],
    ) -> Result<(), BusError>;
}

#[cfg(feature = "async")]
impl<B: AsyncSdoBus + ?Sized> AsyncSdoBus for &mut B {
    async fn upload(
        &mut self,
        node: NodeId,
        index: u16,
        subindex: u8,
        out: &mut [u8],
    ) -> Result<usize, BusError> {
        (**self).upload(node, index, subindex, out).await
    }
    async fn download(
        &mut self,
        node: NodeId,
        index: u16,
        subindex: u8,
        data: &[u8],
    ) -> Result<(), BusError> {
        (**self).download(node, index, subindex, data).await
    }
}

/// An [`SdoBus`] (or, with feature `async`, an [`AsyncSdoBus`]) bound to one node: the [`Link`] generated CANopen drive handles use.
#[derive(Debug)]
pub struct CanOpenLink<B> {
    bus: B,
    node: NodeId,
}

// Unbounded: the same link serves a blocking and an async bus.
impl<B> CanOpenLink<B> {
    /// Binds `bus` to `node`.
    pub fn new(bus: B, node: NodeId) -> Self {
        Self { bus, node }
    }
    /// The node this link talks to.
    pub fn node(&self) -> NodeId {
        self.node
    }
    /// The underlying bus.
    pub fn bus_mut(&mut self) -> &mut B {
        &mut self.bus
    }
}

/// How many bytes an object's value occupies on the wire, as its address says.
fn wire_bytes(address: &ObjectAddress) -> usize {
    address.bytes as usize
}

impl<B: SdoBus> Link for CanOpenLink<B> {
    type Protocol = CanOpen;

    fn read(&mut self, address: &ObjectAddress, out: &mut [u8]) -> Result<usize, BusError> {
        self.bus
            .upload(self.node, address.index, address.subindex, out)
    }

    fn write(&mut self, address: &ObjectAddress, data: &[u8]) -> Result<(), BusError> {
        self.bus
            .download(self.node, address.index, address.subindex, data)
    }

    fn wire_bytes(&self, address: &ObjectAddress) -> usize {
        wire_bytes(address)
    }
}

/// The async twin of the [`Link`] impl: the same calls, awaited.
#[cfg(feature = "async")]
impl<B: AsyncSdoBus> crate::asynch::AsyncLink for CanOpenLink<B> {
    type Protocol = CanOpen;

    async fn read(&mut self, address: &ObjectAddress, out: &mut [u8]) -> Result<usize, BusError> {
        self.bus
            .upload(self.node, address.index, address.subindex, out)
            .await
    }

    async fn write(&mut self, address: &ObjectAddress, data: &[u8]) -> Result<(), BusError> {
        self.bus
            .download(self.node, address.index, address.subindex, data)
            .await
    }

    fn wire_bytes(&self, address: &ObjectAddress) -> usize {
        wire_bytes(address)
    }
}
