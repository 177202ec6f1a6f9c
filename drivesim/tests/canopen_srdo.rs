//! The simulated node's SRDOs, sans-I/O, on the SRDO fixture (the SWD's default SRDO1 RX,
//! SRDO2 TX, SRDO10 invalid): SRDO2 is sent every SCT while Operational, normal then inverted;
//! SRDO1 changes the safety controlword only for a consistent pair within SRVT, and every other
//! case is a refusal.

use std::time::Duration;

use drivebus::canopen::nmt::NmtCommand;
use drivebus::canopen::srdo::SrdoError;
use drivebus::canopen::{CanFrame, NodeId};
use drivesim::canopen::{Node, NodeConfig};
use drivesim::Simulator;

const FIXTURE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../codegen/tests/fixtures/srdo"
);
/// The quick start's node (SWD manual line 4100): SRDO1 on 11Fh / 120h (line 4111).
const NODE: NodeId = NodeId(0x10);

fn ms(n: u64) -> Duration {
    Duration::from_millis(n)
}

fn node() -> (Simulator, Node) {
    let sim = Simulator::load(FIXTURE).unwrap();
    let node = Node::new(
        sim.clone(),
        NodeConfig {
            node: NODE,
            heartbeat: None,
        },
        None,
    );
    (sim, node)
}

fn operational(node: &mut Node, now: Duration) {
    node.boot(now);
    node.handle(&NmtCommand::Start.frame(Some(NODE)), now);
}

fn controlword(sim: &Simulator) -> i128 {
    sim.with(|d| {
        let store = d.store();
        store
            .int(store.id("safety_controlword_1").unwrap())
            .unwrap()
    })
}

fn frame(id: u16, data: &[u8]) -> CanFrame {
    CanFrame::new(id, data).unwrap()
}

#[test]
fn srdo2_is_sent_every_sct_in_operational_only() {
    let (sim, mut node) = node();
    sim.preset("safety_statusword_1", 0x5A).unwrap();
    sim.preset("safety_statusword_8", 0x01).unwrap();
    node.boot(ms(0));
    assert!(
        node.poll_srdo(ms(0)).is_empty(),
        "nothing in Pre-Operational"
    );
    node.handle(&NmtCommand::Start.frame(Some(NODE)), ms(0));
    let pair = node.poll_srdo(ms(1));
    assert_eq!(
        pair,
        [
            frame(0x103, &[0x5A, 0, 0, 0, 0, 0, 0, 0x01]),
            frame(0x104, &[0xA5, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFE]),
        ]
    );
    assert!(node.poll_srdo(ms(25)).is_empty());
    assert_eq!(node.poll_srdo(ms(26)).len(), 2); // SCT 25 ms (line 1760)
    assert!(node.srdos().skipped().is_empty());
}

#[test]
fn srdo1_changes_the_controlword_only_for_a_good_pair() {
    let (sim, mut node) = node();
    operational(&mut node, ms(0));
    let before = controlword(&sim);
    // Disagreeing pair.
    node.handle(&frame(0x11F, &[0x33]), ms(1));
    node.handle(&frame(0x120, &[0x33]), ms(2));
    // Late pair (SRVT 20 ms, line 1739).
    node.handle(&frame(0x11F, &[0x44]), ms(10));
    node.handle(&frame(0x120, &[0xBB]), ms(31));
    assert_eq!(controlword(&sim), before);
    assert_eq!(
        node.srdos()
            .refusals()
            .iter()
            .map(|r| r.1)
            .collect::<Vec<_>>(),
        [
            SrdoError::Inconsistent,
            SrdoError::SrvtExpired {
                waited: ms(21),
                srvt: ms(20)
            }
        ]
    );
    // The quick start's pair (line 4111).
    node.handle(&frame(0x11F, &[0xFF]), ms(40));
    node.handle(&frame(0x120, &[0x00]), ms(41));
    assert_eq!(controlword(&sim), 0xFF);
}

#[test]
fn a_silent_srdo1_expires_its_sct() {
    let (_sim, mut node) = node();
    operational(&mut node, ms(0));
    node.poll_srdo(ms(50));
    assert!(node.srdos().refusals().is_empty());
    node.poll_srdo(ms(51)); // SCT 50 ms (line 1738)
    assert!(matches!(
        node.srdos().refusals(),
        [(1, SrdoError::SctExpired { .. })]
    ));
}

#[test]
fn srdo_frames_are_ignored_outside_operational() {
    let (sim, mut node) = node();
    node.boot(ms(0));
    let before = controlword(&sim);
    node.handle(&frame(0x11F, &[0x12]), ms(1));
    node.handle(&frame(0x120, &[0xED]), ms(2));
    assert_eq!(controlword(&sim), before);
    assert!(node.srdos().refusals().is_empty());
}
