//! The simulated node's PDOs, sans-I/O, on the Kinco description (TPDO1 = position and
//! statusword, type 254, inhibit 1 ms; RPDO1 = target position, mode and controlword, type 254):
//! TPDOs go out only while Operational, on change past the inhibit time or every n-th SYNC as the
//! drive's objects say when it starts (or at once, for a PDO reconfigured while Operational);
//! RPDOs write through the drive's checks, at once or at the next SYNC.

use std::time::Duration;

use drivebus::canopen::nmt::NmtCommand;
use drivebus::canopen::{CanFrame, NodeId};
use drivesim::canopen::{Node, NodeConfig};
use drivesim::Simulator;

const KINCO: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../descriptions/kinco-fd");
const NODE: NodeId = NodeId(1);
const TPDO1: u16 = 0x181;
const RPDO1: u16 = 0x201;
const SYNC: u16 = 0x080;

fn ms(n: u64) -> Duration {
    Duration::from_millis(n)
}

fn frame(id: u16, data: &[u8]) -> CanFrame {
    CanFrame::new(id, data).unwrap()
}

fn node() -> (Simulator, Node) {
    let sim = Simulator::load(KINCO).unwrap();
    let config = NodeConfig {
        node: NODE,
        heartbeat: None,
    };
    let mut node = Node::new(sim.clone(), config, None);
    node.boot(ms(0));
    (sim, node)
}

fn start(node: &mut Node, now: Duration) {
    node.handle(&NmtCommand::Start.frame(Some(NODE)), now);
}

/// An expedited SDO download of `value` (`bytes` wide) to `index:sub`, answered.
fn sdo_write(node: &mut Node, index: u16, sub: u8, value: u32, bytes: u8) {
    let command = 0x23 | ((4 - bytes) << 2);
    let [lo, hi] = index.to_le_bytes();
    let mut data = vec![command, lo, hi, sub];
    data.extend(value.to_le_bytes());
    let answer = node.handle(&frame(0x600 + u16::from(NODE.0), &data), ms(0));
    assert_eq!(answer[0].data()[0], 0x60, "{index:04X}h:{sub} written");
}

fn int(sim: &Simulator, name: &str) -> i128 {
    sim.with(|d| d.store().int(d.store().id(name).unwrap()).unwrap())
}

fn tpdo1(sim: &Simulator) -> Vec<u8> {
    let position = int(sim, "position_actual") as i32;
    let statusword = int(sim, "statusword") as u16;
    [&position.to_le_bytes()[..], &statusword.to_le_bytes()].concat()
}

#[test]
fn an_event_tpdo_goes_out_when_operational_then_on_change_past_the_inhibit_time() {
    let (sim, mut node) = node();
    assert!(node.poll_pdo(ms(1)).is_empty(), "not while pre-operational");
    start(&mut node, ms(2));
    let first = node.poll_pdo(ms(2));
    assert_eq!(first.len(), 1);
    assert_eq!(first[0].id(), TPDO1);
    assert_eq!(first[0].data(), tpdo1(&sim));
    assert!(
        node.poll_pdo(ms(50)).is_empty(),
        "no change, no event timer"
    );

    // RPDO1 (type 254) takes effect at once: target 1000, mode 3, controlword shutdown.
    let rpdo = [0xE8, 0x03, 0x00, 0x00, 0x03, 0x06, 0x00];
    assert!(node.handle(&frame(RPDO1, &rpdo), ms(51)).is_empty());
    assert_eq!(int(&sim, "target_position"), 1000);
    assert_eq!(int(&sim, "modes_of_operation"), 3);
    let before = first[0].data()[4..].to_vec();
    assert_ne!(
        tpdo1(&sim)[4..],
        before,
        "the controlword changed the statusword"
    );
    // Changed: sent at once (the last TPDO is older than the 1 ms inhibit time) ...
    let changed = node.poll_pdo(ms(51));
    assert_eq!(changed.len(), 1);
    assert_eq!(changed[0].data(), tpdo1(&sim));
    // ... and the next change waits for the inhibit time.
    node.handle(
        &frame(RPDO1, &[0xE8, 0x03, 0x00, 0x00, 0x03, 0x07, 0x00]),
        ms(51),
    );
    assert!(node.poll_pdo(Duration::from_micros(51_500)).is_empty());
    assert_eq!(node.poll_pdo(ms(52)).len(), 1);
}

#[test]
fn a_master_configures_a_synchronous_tpdo_and_rpdo_before_starting_the_node() {
    let (sim, mut node) = node();
    sdo_write(&mut node, 0x1800, 2, 2, 1); // TPDO1: every 2nd SYNC
    sdo_write(&mut node, 0x1400, 2, 1, 1); // RPDO1: at the next SYNC
    start(&mut node, ms(0));
    assert!(node.poll_pdo(ms(1)).is_empty(), "not event-driven any more");
    assert!(node.handle(&frame(SYNC, &[]), ms(2)).is_empty(), "1st SYNC");
    let sent = node.handle(&frame(SYNC, &[]), ms(3));
    assert_eq!(sent.len(), 1, "2nd SYNC");
    assert_eq!(sent[0].data(), tpdo1(&sim));

    node.handle(
        &frame(RPDO1, &[0xD0, 0x07, 0x00, 0x00, 0x03, 0x06, 0x00]),
        ms(4),
    );
    assert_eq!(int(&sim, "target_position"), 0, "held until the SYNC");
    node.handle(&frame(SYNC, &[]), ms(5));
    assert_eq!(int(&sim, "target_position"), 2000);
}

#[test]
fn an_invalid_pdo_is_silent_and_a_short_rpdo_is_not_processed() {
    let (sim, mut node) = node();
    sdo_write(&mut node, 0x1800, 1, 0x8000_0181, 4);
    start(&mut node, ms(0));
    assert!(node.poll_pdo(ms(1)).is_empty(), "TPDO1 is not valid");
    node.handle(&frame(RPDO1, &[0xE8, 0x03, 0x00]), ms(2));
    assert_eq!(int(&sim, "target_position"), 0);
    assert_eq!(node.pdos().length_errors(), 1);
    assert!(
        node.pdos().skipped().is_empty(),
        "{:?}",
        node.pdos().skipped()
    );
}

#[test]
fn a_tpdo_remapped_while_operational_takes_the_new_mapping_at_once() {
    let (sim, mut node) = node();
    start(&mut node, ms(0));
    assert_eq!(node.poll_pdo(ms(1)).len(), 1, "TPDO1 as described");
    // The CiA 301 sequence, while Operational: disable, type 1 (every SYNC), remap to the
    // statusword alone, enable.
    sdo_write(&mut node, 0x1800, 1, 0x8000_0181, 4);
    sdo_write(&mut node, 0x1800, 2, 1, 1);
    sdo_write(&mut node, 0x1A00, 0, 0, 1);
    sdo_write(&mut node, 0x1A00, 1, 0x6041_0010, 4);
    sdo_write(&mut node, 0x1A00, 0, 1, 1);
    assert!(
        node.handle(&frame(SYNC, &[]), ms(2)).is_empty(),
        "disabled meanwhile"
    );
    sdo_write(&mut node, 0x1800, 1, 0x181, 4);
    assert!(node.poll_pdo(ms(3)).is_empty(), "not event-driven any more");
    let sent = node.handle(&frame(SYNC, &[]), ms(4));
    assert_eq!(sent.len(), 1, "at the SYNC");
    let statusword = int(&sim, "statusword") as u16;
    assert_eq!(sent[0].data(), statusword.to_le_bytes());
}
