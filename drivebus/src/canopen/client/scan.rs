//! Bus scan: which nodes answer, and who they are. Expedited SDO uploads of the device type
//! (1000h) and the identity object (1018h sub 1-3) go to every candidate node at once; answers are
//! collected until one short timeout ends, so a scan of all 127 node ids takes about one timeout
//! per object, not 127 timeouts in a row.

use std::collections::BTreeMap;
use std::time::{Duration, Instant};
use std::vec::Vec;

use crate::canopen::can::CanBus;
use crate::canopen::frame::CanFrame;
use crate::canopen::NodeId;
use crate::BusError;

/// What a node reported: its device type and identity; an object it did not answer is `None`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NodeIdentity {
    /// The node.
    pub node: NodeId,
    /// Device type (1000h).
    pub device_type: u32,
    /// Vendor-ID (1018h sub 1).
    pub vendor_id: Option<u32>,
    /// Product code (1018h sub 2).
    pub product_code: Option<u32>,
    /// Revision number (1018h sub 3).
    pub revision: Option<u32>,
}

/// Scans `nodes`: the nodes that answer 1000h within `timeout`, with their 1018h entries.
pub fn scan<B: CanBus>(
    bus: &mut B,
    nodes: &[NodeId],
    timeout: Duration,
) -> Result<Vec<NodeIdentity>, BusError> {
    let device_types = upload_all(bus, nodes, 0x1000, 0, timeout)?;
    let found: Vec<NodeId> = device_types.keys().map(|n| NodeId(*n)).collect();
    let mut identity = [BTreeMap::new(), BTreeMap::new(), BTreeMap::new()];
    for (sub, answers) in (1u8..).zip(identity.iter_mut()) {
        *answers = upload_all(bus, &found, 0x1018, sub, timeout)?;
    }
    let [vendor, product, revision] = identity;
    Ok(device_types
        .into_iter()
        .map(|(node, device_type)| NodeIdentity {
            node: NodeId(node),
            device_type,
            vendor_id: vendor.get(&node).copied(),
            product_code: product.get(&node).copied(),
            revision: revision.get(&node).copied(),
        })
        .collect())
}

/// Sends an expedited upload of `index`/`sub` to every node, then collects the 4-byte answers
/// until `timeout` has passed or every node answered. Aborts and other frames are skipped.
fn upload_all<B: CanBus>(
    bus: &mut B,
    nodes: &[NodeId],
    index: u16,
    sub: u8,
    timeout: Duration,
) -> Result<BTreeMap<u8, u32>, BusError> {
    let [lo, hi] = index.to_le_bytes();
    for node in nodes {
        let request = CanFrame::new(
            0x600 + u16::from(node.get()),
            &[0x40, lo, hi, sub, 0, 0, 0, 0],
        )?;
        bus.send(&request)?;
    }
    let deadline = Instant::now() + timeout;
    let mut answers = BTreeMap::new();
    while answers.len() < nodes.len() {
        let left = deadline.saturating_duration_since(Instant::now());
        if left.is_zero() {
            break;
        }
        let Some(frame) = bus.recv(left)? else {
            break;
        };
        if let Some((node, value)) = upload_answer(&frame, index, sub) {
            if nodes.iter().any(|n| n.get() == node) {
                answers.insert(node, value);
            }
        }
    }
    Ok(answers)
}

/// The node and value of an expedited upload response to `index`/`sub`, if `frame` is one.
fn upload_answer(frame: &CanFrame, index: u16, sub: u8) -> Option<(u8, u32)> {
    let node = frame
        .id()
        .checked_sub(0x580)
        .filter(|n| (u16::from(NodeId::MIN)..=u16::from(NodeId::MAX)).contains(n))?;
    let data = frame.data();
    let expedited = data.len() == 8 && data[0] & 0xE2 == 0x42;
    let addressed = u16::from_le_bytes([data.get(1).copied()?, data.get(2).copied()?]) == index
        && data[3] == sub;
    (expedited && addressed).then(|| {
        let unused = if data[0] & 0x01 != 0 {
            (data[0] >> 2) & 0x03
        } else {
            0
        };
        let mut bytes = [0u8; 4];
        let len = 4 - usize::from(unused);
        bytes[..len].copy_from_slice(&data[4..4 + len]);
        (node as u8, u32::from_le_bytes(bytes))
    })
}
