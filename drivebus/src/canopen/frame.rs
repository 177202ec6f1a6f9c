//! Classic CAN frames with 11-bit identifiers, and the CiA 301 predefined connection set.

use crate::error::BusError;

/// Highest 11-bit identifier.
pub const MAX_ID: u16 = drivebus_model::canopen::MAX_COB_ID;

/// A classic CAN frame: 11-bit identifier, remote flag, up to 8 data bytes.
///
/// Bytes past `len` are always zero, so frames compare equal exactly when they are equal on the
/// wire.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct CanFrame {
    id: u16,
    rtr: bool,
    len: u8,
    data: [u8; 8],
}

impl CanFrame {
    /// A data frame; fails if `id` exceeds 11 bits or `data` exceeds 8 bytes.
    pub fn new(id: u16, data: &[u8]) -> Result<Self, BusError> {
        let mut bytes = [0u8; 8];
        bytes
            .get_mut(..data.len())
            .ok_or(BusError::Frame("CAN payload exceeds 8 bytes"))?
            .copy_from_slice(data);
        Self::from_buffer(id, bytes, data.len())
    }

    /// A data frame of the first `len` bytes of `data` (the rest zeroed); fails as [`Self::new`]
    /// does. For a parser that fills an 8-byte buffer: no copy of a slice of run-time length,
    /// which is a `memcpy` call per frame (`drivegen trace` reads millions, issue 33).
    pub(crate) fn from_buffer(id: u16, data: [u8; 8], len: usize) -> Result<Self, BusError> {
        if id > MAX_ID {
            return Err(BusError::Frame("CAN id exceeds 11 bits"));
        }
        let kept = match len {
            0..=7 => (1u64 << (8 * len)) - 1,
            8 => u64::MAX,
            _ => return Err(BusError::Frame("CAN payload exceeds 8 bytes")),
        };
        Ok(Self {
            id,
            rtr: false,
            len: len as u8,
            data: (u64::from_le_bytes(data) & kept).to_le_bytes(),
        })
    }

    /// A remote (RTR) frame asking for `len` bytes.
    pub fn remote(id: u16, len: u8) -> Result<Self, BusError> {
        if id > MAX_ID {
            return Err(BusError::Frame("CAN id exceeds 11 bits"));
        }
        if len > 8 {
            return Err(BusError::Frame("CAN DLC exceeds 8"));
        }
        Ok(Self {
            id,
            rtr: true,
            len,
            data: [0; 8],
        })
    }

    /// A full 8-byte data frame; the protocol cores build their frames with this, the id being
    /// derived from a valid node id.
    pub(crate) const fn full(id: u16, data: [u8; 8]) -> Self {
        Self {
            id: id & MAX_ID,
            rtr: false,
            len: 8,
            data,
        }
    }

    /// The same frame cut to `len` bytes (at most 8), the rest zeroed.
    pub(crate) const fn truncated(mut self, len: u8) -> Self {
        let len = if len > 8 { 8 } else { len };
        let mut i = len as usize;
        while i < 8 {
            self.data[i] = 0;
            i += 1;
        }
        self.len = len;
        self
    }

    /// The 11-bit identifier.
    pub const fn id(&self) -> u16 {
        self.id
    }
    /// Whether this is a remote frame.
    pub const fn is_remote(&self) -> bool {
        self.rtr
    }
    /// The data length code (0..=8).
    pub const fn dlc(&self) -> u8 {
        self.len
    }
    /// The payload (empty for remote frames).
    pub fn data(&self) -> &[u8] {
        if self.rtr {
            &[]
        } else {
            &self.data[..self.len as usize]
        }
    }
    /// The payload padded with zeros to 8 bytes.
    pub const fn padded(&self) -> [u8; 8] {
        self.data
    }
}

/// Function codes of the predefined connection set: COB-ID = function code + node id.
pub mod cob {
    /// NMT node control (master → nodes).
    pub const NMT: u16 = 0x000;
    /// SYNC.
    pub const SYNC: u16 = 0x080;
    /// EMCY base (0x081..=0x0FF).
    pub const EMCY: u16 = 0x080;
    /// TIME stamp.
    pub const TIME: u16 = 0x100;
    /// TPDO1..4 bases (node → master).
    pub const TPDO: [u16; 4] = [0x180, 0x280, 0x380, 0x480];
    /// RPDO1..4 bases (master → node).
    pub const RPDO: [u16; 4] = [0x200, 0x300, 0x400, 0x500];
    /// SDO server → client.
    pub const SDO_TX: u16 = 0x580;
    /// SDO client → server.
    pub const SDO_RX: u16 = 0x600;
    /// NMT error control: heartbeat, boot-up and node guarding.
    pub const HEARTBEAT: u16 = 0x700;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    #[cfg(feature = "canopen")]
    fn from_buffer_is_new_of_the_buffer_s_first_bytes() {
        let buffer = [0x11, 0x22, 0x33, 0x44, 0x55, 0x66, 0x77, 0x88];
        for len in 0..=8 {
            let frame = CanFrame::from_buffer(0x7FF, buffer, len).unwrap();
            // The bytes past `len` zeroed, as `new` leaves them: equal frames compare equal.
            assert_eq!(
                frame,
                CanFrame::new(0x7FF, &buffer[..len]).unwrap(),
                "{len}"
            );
        }
        assert!(CanFrame::from_buffer(0x800, buffer, 1).is_err());
        assert!(CanFrame::from_buffer(0x123, buffer, 9).is_err());
    }
}
