//! Bus scan: which nodes answer, and who they are. An expedited SDO upload of the device type
//! (1000h) goes to every candidate node at once; each node that answers is then asked for its
//! identity (1018h sub 1-3) at once, one object after the other, while the scan still waits for
//! the others. So a scan of all 127 node ids takes about one timeout (the silence of the
//! missing ids), not one timeout per object nor 127 timeouts in a row.

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

/// The objects asked of every node, in order: the device type, then the identity.
const STEPS: [(u16, u8); 4] = [(0x1000, 0), (0x1018, 1), (0x1018, 2), (0x1018, 3)];

/// One node's scan: which object it is asked for, until when, and what it answered so far.
#[derive(Debug, Clone, Copy)]
struct Probe {
    node: NodeId,
    step: usize,
    deadline: Instant,
    answers: [Option<u32>; 4],
}

impl Probe {
    fn done(&self) -> bool {
        self.step >= STEPS.len()
    }

    fn identity(&self) -> Option<NodeIdentity> {
        let [device_type, vendor_id, product_code, revision] = self.answers;
        Some(NodeIdentity {
            node: self.node,
            device_type: device_type?,
            vendor_id,
            product_code,
            revision,
        })
    }
}

/// Scans `nodes`: the nodes that answer 1000h within `timeout`, with their 1018h entries (each
/// also given `timeout`; an abort or silence leaves it `None`).
pub fn scan<B: CanBus>(
    bus: &mut B,
    nodes: &[NodeId],
    timeout: Duration,
) -> Result<Vec<NodeIdentity>, BusError> {
    let start = Instant::now() + timeout;
    let mut probes: BTreeMap<u8, Probe> = nodes
        .iter()
        .map(|&node| {
            let probe = Probe {
                node,
                step: 0,
                deadline: start,
                answers: [None; 4],
            };
            (node.get(), probe)
        })
        .collect();
    for probe in probes.values() {
        bus.send(&request(probe)?)?;
    }
    while let Some(deadline) = probes
        .values()
        .filter(|p| !p.done())
        .map(|p| p.deadline)
        .min()
    {
        let left = deadline.saturating_duration_since(Instant::now());
        match bus.recv(left)? {
            Some(frame) => {
                let Some((node, answer)) = answer(&frame) else {
                    continue;
                };
                let Some(probe) = probes.get_mut(&node).filter(|p| !p.done()) else {
                    continue;
                };
                if answer.object == STEPS[probe.step] {
                    probe.answers[probe.step] = answer.value;
                    advance(bus, probe, timeout)?;
                }
            }
            None => {
                let now = Instant::now();
                for probe in probes
                    .values_mut()
                    .filter(|p| !p.done() && p.deadline <= now)
                {
                    advance(bus, probe, timeout)?;
                }
            }
        }
    }
    Ok(probes.values().filter_map(Probe::identity).collect())
}

/// Moves `probe` to its next object and asks for it; a node that did not answer 1000h is done.
fn advance<B: CanBus>(bus: &mut B, probe: &mut Probe, timeout: Duration) -> Result<(), BusError> {
    probe.step = if probe.answers[0].is_none() {
        STEPS.len()
    } else {
        probe.step + 1
    };
    if !probe.done() {
        probe.deadline = Instant::now() + timeout;
        bus.send(&request(probe)?)?;
    }
    Ok(())
}

/// The expedited upload request of `probe`'s current object.
fn request(probe: &Probe) -> Result<CanFrame, BusError> {
    let (index, sub) = STEPS[probe.step];
    let [lo, hi] = index.to_le_bytes();
    CanFrame::new(
        0x600 + u16::from(probe.node.get()),
        &[0x40, lo, hi, sub, 0, 0, 0, 0],
    )
}

/// An answer to an upload request: the object, and its value (`None` for an abort).
struct Answer {
    object: (u16, u8),
    value: Option<u32>,
}

/// The node and answer of an expedited upload response or an abort, if `frame` is one.
fn answer(frame: &CanFrame) -> Option<(u8, Answer)> {
    let node = frame
        .id()
        .checked_sub(0x580)
        .filter(|n| (u16::from(NodeId::MIN)..=u16::from(NodeId::MAX)).contains(n))?;
    let data = frame.data();
    if data.len() != 8 {
        return None;
    }
    let object = (u16::from_le_bytes([data[1], data[2]]), data[3]);
    let value = match data[0] {
        0x80 => None,
        command if command & 0xE2 == 0x42 => {
            let unused = if command & 0x01 != 0 {
                (command >> 2) & 0x03
            } else {
                0
            };
            let mut bytes = [0u8; 4];
            let len = 4 - usize::from(unused);
            bytes[..len].copy_from_slice(&data[4..4 + len]);
            Some(u32::from_le_bytes(bytes))
        }
        _ => return None,
    };
    Some((node as u8, Answer { object, value }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn expedited_answers_and_aborts_are_told_apart() {
        let value = CanFrame::new(0x585, &[0x4F, 0x18, 0x10, 0x01, 0x15, 0, 0, 0]).unwrap();
        let (node, got) = answer(&value).unwrap();
        assert_eq!((node, got.object, got.value), (5, (0x1018, 1), Some(0x15)));
        let abort = CanFrame::new(0x585, &[0x80, 0x18, 0x10, 0x02, 0, 0, 2, 6]).unwrap();
        let (_, got) = answer(&abort).unwrap();
        assert_eq!((got.object, got.value), ((0x1018, 2), None));
        let segmented = CanFrame::new(0x585, &[0x41, 0x00, 0x10, 0x00, 4, 0, 0, 0]).unwrap();
        assert!(answer(&segmented).is_none());
        let request = CanFrame::new(0x605, &[0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0]).unwrap();
        assert!(answer(&request).is_none());
    }
}
