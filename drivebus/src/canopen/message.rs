//! Classifies any frame of the CiA 301 predefined connection set into a typed message, for
//! monitoring, logging and offline decoding of candump logs.

use super::address::NodeId;
use super::emcy::Emcy;
use super::frame::{cob, CanFrame};
use super::nmt::{decode_heartbeat, NmtCommand, NmtState};
use super::sdo::{scs, specifier};

/// A frame of the predefined connection set, decoded.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Message {
    /// NMT node control.
    Nmt {
        /// The command.
        command: NmtCommand,
        /// Its target; `None` = all nodes.
        target: Option<NodeId>,
    },
    /// SYNC, with its counter if any.
    Sync(Option<u8>),
    /// Emergency.
    Emcy(Emcy),
    /// TIME stamp (payload kept raw).
    Time(CanFrame),
    /// A PDO of the default connection set.
    Pdo {
        /// Receive (master → node) or transmit (node → master).
        kind: super::pdo::PdoKind,
        /// 1..=4.
        number: u8,
        /// The node.
        node: NodeId,
        /// The frame, for a [`PdoLayout`](super::pdo::PdoLayout) to decode.
        frame: CanFrame,
    },
    /// An SDO response (server → client).
    SdoResponse {
        /// The server node.
        node: NodeId,
        /// The 8 data bytes.
        data: [u8; 8],
    },
    /// An SDO request (client → server).
    SdoRequest {
        /// The server node.
        node: NodeId,
        /// The 8 data bytes.
        data: [u8; 8],
    },
    /// Heartbeat, boot-up or node-guarding answer.
    Heartbeat {
        /// The node.
        node: NodeId,
        /// The state it reports.
        state: NmtState,
    },
    /// Anything else (other COB-IDs, malformed frames of known ones).
    Other(CanFrame),
}

/// A value carried in an expedited SDO upload response.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ExpeditedValue {
    /// Object index.
    pub index: u16,
    /// Subindex.
    pub subindex: u8,
    /// Valid bytes of `bytes`.
    pub len: u8,
    /// Little-endian value bytes.
    pub bytes: [u8; 4],
}

impl ExpeditedValue {
    /// The value as an unsigned integer.
    pub const fn as_u32(&self) -> u32 {
        u32::from_le_bytes(self.bytes)
    }
}

fn node_of(id: u16, base: u16) -> NodeId {
    NodeId((id - base) as u8)
}

impl Message {
    /// Decodes `frame`.
    pub fn classify(frame: &CanFrame) -> Self {
        let id = frame.id();
        let (function, node) = (id & 0x780, (id & 0x7F) as u8);
        let other = Self::Other(*frame);
        if frame.is_remote() {
            return other;
        }
        match function {
            0x000 if id == cob::NMT => NmtCommand::decode(frame)
                .map_or(other, |(command, target)| Self::Nmt { command, target }),
            0x080 if node == 0 => match frame.dlc() {
                0 => Self::Sync(None),
                1 => Self::Sync(Some(frame.data()[0])),
                _ => other,
            },
            0x080 => Emcy::decode(frame).map_or(other, Self::Emcy),
            0x100 if node == 0 => Self::Time(*frame),
            0x180 | 0x280 | 0x380 | 0x480 | 0x200 | 0x300 | 0x400 | 0x500 if node != 0 => {
                let transmit = function & 0x80 != 0;
                Self::Pdo {
                    kind: if transmit {
                        super::pdo::PdoKind::Transmit
                    } else {
                        super::pdo::PdoKind::Receive
                    },
                    number: (((function >> 8) as u8) - u8::from(!transmit)).max(1),
                    node: NodeId(node),
                    frame: *frame,
                }
            }
            0x580 if node != 0 && frame.dlc() == 8 => Self::SdoResponse {
                node: node_of(id, cob::SDO_TX),
                data: frame.padded(),
            },
            0x600 if node != 0 && frame.dlc() == 8 => Self::SdoRequest {
                node: node_of(id, cob::SDO_RX),
                data: frame.padded(),
            },
            0x700 => decode_heartbeat(frame)
                .map_or(other, |(node, state)| Self::Heartbeat { node, state }),
            _ => other,
        }
    }

    /// The value of an expedited upload response, if this is one.
    pub fn expedited_value(&self) -> Option<ExpeditedValue> {
        let Self::SdoResponse { data, .. } = self else {
            return None;
        };
        // scs = 2, e = 1.
        if specifier(data) != scs::INITIATE_UPLOAD || data[0] & 0b10 == 0 {
            return None;
        }
        let len = if data[0] & 1 != 0 {
            4 - ((data[0] >> 2) & 0b11)
        } else {
            4
        };
        let mut bytes = [0u8; 4];
        bytes[..len as usize].copy_from_slice(&data[4..4 + len as usize]);
        Some(ExpeditedValue {
            index: u16::from_le_bytes([data[1], data[2]]),
            subindex: data[3],
            len,
            bytes,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::super::pdo::PdoKind;
    use super::*;

    fn frame(id: u16, data: &[u8]) -> CanFrame {
        CanFrame::new(id, data).unwrap()
    }

    #[test]
    fn classifies_the_predefined_connection_set() {
        assert!(matches!(
            Message::classify(&frame(0, &[1, 5])),
            Message::Nmt {
                command: NmtCommand::Start,
                target: Some(NodeId(5))
            }
        ));
        assert_eq!(Message::classify(&frame(0x80, &[])), Message::Sync(None));
        assert_eq!(
            Message::classify(&frame(0x80, &[7])),
            Message::Sync(Some(7))
        );
        assert!(
            matches!(Message::classify(&frame(0x85, &[0x10, 0x23, 1, 0, 0, 0, 0, 0])), Message::Emcy(e) if e.code == 0x2310)
        );
        assert!(matches!(
            Message::classify(&frame(0x100, &[0; 6])),
            Message::Time(_)
        ));
        for (id, kind, number) in [
            (0x185, PdoKind::Transmit, 1),
            (0x285, PdoKind::Transmit, 2),
            (0x485, PdoKind::Transmit, 4),
            (0x205, PdoKind::Receive, 1),
            (0x505, PdoKind::Receive, 4),
        ] {
            match Message::classify(&frame(id, &[1, 2])) {
                Message::Pdo {
                    kind: k,
                    number: n,
                    node,
                    ..
                } => assert_eq!((k, n, node), (kind, number, NodeId(5))),
                other => panic!("{id:#x} classified as {other:?}"),
            }
        }
        assert_eq!(
            Message::classify(&frame(0x705, &[5])),
            Message::Heartbeat {
                node: NodeId(5),
                state: NmtState::Operational
            }
        );
        assert!(matches!(
            Message::classify(&frame(0x605, &[0x40, 0, 0x10, 0, 0, 0, 0, 0])),
            Message::SdoRequest {
                node: NodeId(5),
                ..
            }
        ));
        assert!(matches!(
            Message::classify(&frame(0x7E5, &[0])),
            Message::Other(_)
        ));
        assert!(matches!(
            Message::classify(&frame(0x585, &[0x43])),
            Message::Other(_)
        ));
        assert!(matches!(
            Message::classify(&CanFrame::remote(0x185, 8).unwrap()),
            Message::Other(_)
        ));
    }

    #[test]
    fn expedited_upload_values() {
        let reply = Message::classify(&frame(0x581, &[0x4B, 0x41, 0x60, 0, 0x37, 0x02, 0, 0]));
        let value = reply.expedited_value().unwrap();
        assert_eq!(
            (value.index, value.subindex, value.len, value.as_u32()),
            (0x6041, 0, 2, 0x0237)
        );
        let segmented = Message::classify(&frame(0x581, &[0x41, 0x08, 0x10, 0, 20, 0, 0, 0]));
        assert_eq!(segmented.expedited_value(), None);
    }
}
