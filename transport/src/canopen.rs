//! CANopen addressing and the SDO-bus trait that CANopen transports implement.

use crate::error::BusError;
use crate::link::Link;
use crate::Protocol;

/// The CANopen protocol marker.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CanOpen;

impl Protocol for CanOpen {
    type Address = ObjectAddress;
    const NAME: &'static str = "CANopen";
}

/// An object dictionary entry.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ObjectAddress {
    /// Object index.
    pub index: u16,
    /// Subindex.
    pub subindex: u8,
    /// Size in bytes on the wire (odd widths such as 3 for INTEGER24 included); 0 = variable.
    pub bytes: u16,
}

/// A CANopen node id (1..=127).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct NodeId(pub u8);

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
