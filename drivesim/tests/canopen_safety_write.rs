//! drivebus's deliberate safety write against the simulated node (the SRDO fixture, node 10h):
//! the SWD quick start disables SRDO1, re-signs it (BABDh) and marks the configuration valid
//! (line 4111), after which the node enters Operational and no longer consumes SRDO1; a plain
//! SDO write of the same direction invalidates the configuration (13FEh = 00h, line 3581) and
//! the node refuses Operational (line 3568).

use std::collections::VecDeque;
use std::time::Duration;

use drivebus::canopen::client::BlockingSdo;
use drivebus::canopen::nmt::{NmtCommand, NmtState};
use drivebus::canopen::pdo::MappedObject;
use drivebus::canopen::srdo::{
    write_safety_configuration, MappingWrite, SrdoCommunication, SrdoConfig, SrdoDirection,
};
use drivebus::canopen::{CanBus, CanFrame, NodeId, SdoBus};
use drivebus::BusError;
use drivesim::canopen::{Node, NodeConfig};
use drivesim::Simulator;

const FIXTURE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../codegen/tests/fixtures/srdo"
);
const NODE: NodeId = NodeId(0x10);

/// The node itself as a CAN bus: what the client sends, the node handles at once.
struct Direct {
    node: Node,
    replies: VecDeque<CanFrame>,
}

impl CanBus for Direct {
    fn send(&mut self, frame: &CanFrame) -> Result<(), BusError> {
        let replies = self.node.handle(frame, Duration::ZERO);
        self.replies.extend(replies);
        Ok(())
    }
    fn recv(&mut self, _timeout: Duration) -> Result<Option<CanFrame>, BusError> {
        Ok(self.replies.pop_front())
    }
}

fn booted() -> BlockingSdo<Direct> {
    let sim = Simulator::load(FIXTURE).unwrap();
    let config = NodeConfig {
        node: NODE,
        heartbeat: None,
    };
    let mut node = Node::new(sim, config, None);
    node.boot(Duration::ZERO);
    BlockingSdo::new(Direct {
        node,
        replies: VecDeque::new(),
    })
}

const SRDO1_MAPPING: [MappedObject; 2] = [
    MappedObject::from_entry(0x6620_0108),
    MappedObject::from_entry(0x6622_0108),
];

fn disabled_srdo1() -> SrdoConfig<'static> {
    SrdoConfig {
        number: 1,
        communication: SrdoCommunication {
            direction: SrdoDirection::Invalid,
            sct_ms: 50,
            srvt_ms: 20,
            transmission_type: 0xFE,
            cob_id_normal: 0x11F,
            cob_id_inverted: 0x120,
        },
        mapping: &SRDO1_MAPPING,
    }
}

fn read_u16(sdo: &mut BlockingSdo<Direct>, index: u16, subindex: u8) -> u16 {
    let mut buf = [0u8; 2];
    sdo.upload(NODE, index, subindex, &mut buf).unwrap();
    u16::from_le_bytes(buf)
}

fn start(sdo: &mut BlockingSdo<Direct>) -> NmtState {
    let node = &mut sdo.bus_mut().node;
    node.handle(&NmtCommand::Start.frame(Some(NODE)), Duration::ZERO);
    node.state()
}

#[test]
fn quick_start_safety_write_lets_the_node_start_without_srdo1() {
    let mut sdo = booted();
    let state = sdo.bus_mut().node.state();
    assert_eq!(state, NmtState::PreOperational);
    let written =
        write_safety_configuration(&mut sdo, NODE, state, disabled_srdo1(), MappingWrite::Keep);
    assert_eq!(written, Ok(0xBABD));
    assert_eq!(read_u16(&mut sdo, 0x13FF, 1), 0xBABD);
    assert_eq!(read_u16(&mut sdo, 0x13FE, 0) & 0xFF, 0xA5);
    assert_eq!(start(&mut sdo), NmtState::Operational);
    let node = &mut sdo.bus_mut().node;
    // SRDO1 is no longer consumed: its frames are not SRDO frames, and silence is no SCT error.
    node.handle(
        &CanFrame::new(0x11F, &[0xFF]).unwrap(),
        Duration::from_millis(1),
    );
    node.poll_srdo(Duration::from_millis(500));
    assert!(node.srdos().refusals().is_empty());
}

#[test]
fn a_plain_write_invalidates_the_configuration_and_blocks_operational() {
    let mut sdo = booted();
    sdo.download(NODE, 0x1301, 1, &[0]).unwrap();
    assert_eq!(read_u16(&mut sdo, 0x13FE, 0) & 0xFF, 0x00);
    assert_eq!(start(&mut sdo), NmtState::PreOperational);
}

#[test]
fn a_valid_flag_with_a_stale_signature_blocks_operational() {
    let mut sdo = booted();
    sdo.download(NODE, 0x1301, 1, &[0]).unwrap();
    sdo.download(NODE, 0x13FE, 0, &[0xA5]).unwrap();
    assert_eq!(start(&mut sdo), NmtState::PreOperational);
}

#[test]
fn the_default_configuration_starts() {
    let mut sdo = booted();
    assert_eq!(start(&mut sdo), NmtState::Operational);
}
