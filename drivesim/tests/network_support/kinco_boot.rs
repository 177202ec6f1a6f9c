//! The boot the PDO boot tests give a simulated Kinco.

use std::time::Duration;

use drivebus::canopen::network::boot::{BootWrite, NodeBoot};
use drivebus::canopen::pdo::{MappedObject, PdoKind, PdoSetup};
use drivebus::canopen::NodeId;

/// Heartbeat 100 ms; TPDO1 = statusword (6041h, 16 bits) and mode display (6061h, 8 bits),
/// type 254, every 20 ms, at the predefined connection set's COB-ID; profile speed (6081h) =
/// 1234 raw; started. No identity check.
pub fn plan(node: NodeId) -> NodeBoot {
    NodeBoot {
        heartbeat: Some(Duration::from_millis(100)),
        pdos: vec![PdoSetup {
            kind: PdoKind::Transmit,
            number: 1,
            cob_id: PdoSetup::default_cob_id(PdoKind::Transmit, 1, node.get()).unwrap(),
            transmission_type: Some(254),
            inhibit_time: None,
            event_timer: Some(20),
            entries: vec![
                MappedObject::new(0x6041, 0, 16),
                MappedObject::new(0x6061, 0, 8),
            ],
        }],
        writes: vec![BootWrite {
            index: 0x6081,
            subindex: 0,
            data: 1234u32.to_le_bytes().to_vec(),
        }],
        ..NodeBoot::new(node)
    }
}
