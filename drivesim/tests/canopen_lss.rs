//! The simulated LSS slave (CiA 305) against drivebus's LSS master: the SWD, an LSS slave per
//! its manual (lines 1035, 1068, 4006-4010), answers from its 1018h identity, takes a node id
//! and keeps it across a power cycle only once stored; unconfigured nodes are silent until
//! Fastscan finds them and they get a node id. The Lafert, whose manual names no LSS, ignores it.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::Duration;

use drivebus::canopen::can::in_process::{InProcessBus, InProcessEndpoint};
use drivebus::canopen::client::lss::BlockingLss;
use drivebus::canopen::lss::{
    Command, Fastscan, FastscanProgress, IdentityWord, LssAddress, LssMode, NewNodeId,
};
use drivebus::canopen::nmt::NmtCommand;
use drivebus::canopen::{CanFrame, NodeId};
use drivesim::canopen::{nodes, Node, NodeConfig};
use drivesim::Simulator;

const MS: Duration = Duration::from_millis(1);

fn swd(serial: i128) -> Simulator {
    let path = format!("{}/../descriptions/ezwheel-swd", env!("CARGO_MANIFEST_DIR"));
    let sim = Simulator::load(path).unwrap();
    sim.preset("vendor_id", 0x515).unwrap();
    sim.preset("serial_number", serial).unwrap();
    sim
}

fn node(sim: Simulator, id: u8) -> Node {
    let config = NodeConfig {
        node: NodeId(id),
        heartbeat: None,
    };
    Node::new(sim.clone(), config, sim.variant())
}

/// Runs `nodes` on their own endpoint of `bus` until `stop`.
fn serve(bus: &InProcessBus, mut nodes: Vec<Node>, stop: &Arc<AtomicBool>) -> JoinHandle<()> {
    let mut endpoint = bus.endpoint();
    let flag = Arc::clone(stop);
    std::thread::spawn(move || {
        nodes::run_while(&mut nodes, &mut endpoint, || !flag.load(Ordering::Relaxed)).unwrap();
    })
}

/// The blocking master on a real clock; its answers come from nodes served by [`serve`].
fn master(bus: &InProcessBus) -> BlockingLss<InProcessEndpoint> {
    BlockingLss::new(bus.endpoint()).with_timeout(500 * MS)
}

fn lss(node: &mut Node, command: Command) -> Vec<CanFrame> {
    node.handle(&command.encode(), Duration::ZERO)
}

/// The Fastscan step, in simulated time.
const STEP: Duration = Duration::from_millis(10);

/// `frame` delivered to every node at `now`: their answers.
fn broadcast(nodes: &mut [Node], frame: &CanFrame, now: Duration) -> Vec<CanFrame> {
    nodes
        .iter_mut()
        .flat_map(|n| n.handle(frame, now))
        .collect()
}

/// An SDO upload request of 1018h sub 1 (vendor-ID) to node `id`.
fn vendor_id_request(id: u16) -> CanFrame {
    CanFrame::new(0x600 + id, &[0x40, 0x18, 0x10, 1, 0, 0, 0, 0]).unwrap()
}

/// Drivebus's Fastscan driven in lockstep with the nodes, sans-I/O, in simulated time: each
/// request reaches every node and every answer is in before the step's time passes. In Fastscan
/// silence is an answer, so on a real clock a step the simulator's thread answers late (a
/// loaded machine) loses the node; here the outcome depends on the protocol only. (The blocking
/// master on a real clock is covered by the CLI's `lss` test and python canopen's LssMaster.)
fn fastscan(nodes: &mut [Node], now: &mut Duration) -> FastscanProgress {
    let mut scan = Fastscan::new(STEP, *now);
    loop {
        while let Some(request) = scan.poll_transmit() {
            for answer in broadcast(nodes, &request, *now) {
                scan.handle(&answer, *now);
            }
        }
        let Some(deadline) = scan.deadline() else {
            return scan.progress();
        };
        *now = (*now).max(deadline);
        scan.handle_timeout(*now);
    }
}

#[test]
fn fastscan_finds_two_unconfigured_swds_and_gives_them_ids_20_and_21() {
    let mut nodes = vec![
        node(swd(0x2222), 1).lss_unconfigured(),
        node(swd(0x1111), 2).lss_unconfigured(),
    ];
    let mut now = Duration::ZERO;
    for id in [1, 2] {
        let answers = broadcast(&mut nodes, &vendor_id_request(id), now);
        assert!(answers.is_empty(), "silent before LSS");
    }
    let identify = Command::IdentifyNonConfigured.encode();
    assert_eq!(broadcast(&mut nodes, &identify, now).len(), 2);
    let mut found = Vec::new();
    for id in [20, 21] {
        let FastscanProgress::Found(address) = fastscan(&mut nodes, &mut now) else {
            panic!("an unconfigured node is found");
        };
        let configure = Command::ConfigureNodeId(NewNodeId::new(id).unwrap()).encode();
        let answers = broadcast(&mut nodes, &configure, now);
        assert_eq!(answers.len(), 1, "only the node Fastscan selected answers");
        let waiting = Command::SwitchGlobal(LssMode::Waiting).encode();
        broadcast(&mut nodes, &waiting, now);
        found.push((address.serial, id));
    }
    assert_eq!(fastscan(&mut nodes, &mut now), FastscanProgress::NoneLeft);
    assert_eq!(found, [(0x1111, 20), (0x2222, 21)]);
    for id in [20, 21] {
        let answers = broadcast(&mut nodes, &vendor_id_request(id), now);
        assert_eq!(answers.len(), 1, "node {id} answers SDO at its new id");
        assert_eq!(answers[0].id(), 0x580 + id);
        assert_eq!(answers[0].data()[4..8], 0x515u32.to_le_bytes());
    }
}

#[test]
fn a_node_id_is_kept_across_a_power_cycle_only_once_stored() {
    let mut swd = node(swd(42), 16);
    let address = swd.lss().expect("the SWD is an LSS slave").address();
    assert_eq!(
        address,
        LssAddress {
            vendor_id: 0x515,
            serial: 42,
            ..address
        }
    );
    for (word, value) in IdentityWord::ALL.into_iter().zip(address.words()) {
        lss(&mut swd, Command::SwitchSelective(word, value));
    }
    assert_eq!(
        lss(&mut swd, Command::InquireNodeId)[0].data()[..2],
        [0x5E, 16]
    );
    let five = NewNodeId::new(5).unwrap();
    assert_eq!(
        lss(&mut swd, Command::ConfigureNodeId(five))[0].data()[..2],
        [0x11, 0]
    );
    let reset = NmtCommand::ResetNode.frame(Some(NodeId(16)));
    let boot = swd.handle(&reset, Duration::ZERO);
    assert_eq!(
        boot[0].id(),
        0x705,
        "an NMT reset activates the configured id"
    );
    assert_eq!(
        swd.power_cycle(Duration::ZERO).unwrap().id(),
        0x710,
        "not stored: back to 16"
    );

    for (word, value) in IdentityWord::ALL.into_iter().zip(address.words()) {
        lss(&mut swd, Command::SwitchSelective(word, value));
    }
    lss(&mut swd, Command::ConfigureNodeId(five));
    assert_eq!(lss(&mut swd, Command::Store)[0].data()[..2], [0x17, 0]);
    assert_eq!(
        swd.power_cycle(Duration::ZERO).unwrap().id(),
        0x705,
        "stored: 5"
    );
    assert_eq!(swd.node_id(), Some(NodeId(5)));
}

#[test]
fn a_drive_whose_manual_names_no_lss_ignores_it() {
    let path = format!(
        "{}/../descriptions/lafert-smartris",
        env!("CARGO_MANIFEST_DIR")
    );
    let mut lafert = node(Simulator::load(path).unwrap(), 1).lss_unconfigured();
    assert!(lafert.lss().is_none());
    assert_eq!(
        lafert.node_id(),
        Some(NodeId(1)),
        "no LSS, so never unconfigured"
    );
    assert!(lss(&mut lafert, Command::SwitchGlobal(LssMode::Configuration)).is_empty());
    assert!(lss(&mut lafert, Command::InquireNodeId).is_empty());
}

#[test]
fn the_swd_refuses_a_bit_rate_its_manual_does_not_list() {
    let mut swd = node(swd(7), 16);
    lss(&mut swd, Command::SwitchGlobal(LssMode::Configuration));
    let k100 = Command::ConfigureBitTiming { table: 0, index: 5 };
    assert_eq!(
        lss(&mut swd, k100)[0].data()[..2],
        [0x13, 1],
        "100k: code 1"
    );
    let k250 = Command::ConfigureBitTiming { table: 0, index: 3 };
    assert_eq!(
        lss(&mut swd, k250)[0].data()[..2],
        [0x13, 0],
        "250k: line 1054"
    );
}

#[test]
fn two_drives_with_one_lss_address_make_a_selective_switch_fail() {
    let bus = InProcessBus::new();
    let stop = Arc::new(AtomicBool::new(false));
    let twins = vec![node(swd(9), 16), node(swd(9), 17)];
    let address = twins[0].lss().unwrap().address();
    let server = serve(&bus, twins, &stop);
    let mut lss = master(&bus);
    let result = lss.switch_selective(address);
    let missing = lss.switch_selective(LssAddress {
        serial: 10,
        ..address
    });
    stop.store(true, Ordering::Relaxed);
    server.join().unwrap();
    assert_eq!(
        result,
        Err(drivebus::canopen::lss::LssError::SeveralAnswers)
    );
    assert_eq!(missing, Err(drivebus::canopen::lss::LssError::NoAnswer));
}
