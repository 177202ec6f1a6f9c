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

/// An [`SdoBus`] bound to one node: the [`Link`] generated CANopen drive handles use.
#[derive(Debug)]
pub struct CanOpenLink<B> {
    bus: B,
    node: NodeId,
}

impl<B: SdoBus> CanOpenLink<B> {
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
        address.bytes as usize
    }
}
