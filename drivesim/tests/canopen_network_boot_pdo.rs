//! Network boot with PDOs against a simulated Kinco on one bus: the boot configures TPDO1
//! (statusword and mode display, event timer 20 ms) between the heartbeat and the boot
//! parameters, through `PdoConfig`; once started the node sends that TPDO with the mapped
//! values. Booting again compares first and sends no SDO download at all. A PDO write the node
//! refuses ends the boot with the PDO's step and the abort.

mod network_support;

use std::time::Duration;

use drivebus::canopen::can::in_process::InProcessBus;
use drivebus::canopen::network::boot::boot_node;
use drivebus::canopen::network::{Network, NetworkEvent};
use drivebus::canopen::{CanBus, NodeId};
use drivesim::canopen::{Node, NodeConfig};
use drivesim::Simulator;
use network_support::{kinco_boot, Serving};

const KINCO: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../descriptions/kinco-fd");
const TIMEOUT: Duration = Duration::from_millis(1000);
const NODE: NodeId = NodeId(3);

fn kinco() -> (Simulator, Node) {
    let sim = Simulator::load(KINCO).unwrap();
    let config = NodeConfig {
        node: NODE,
        heartbeat: None,
    };
    let node = Node::new(sim.clone(), config, None);
    (sim, node)
}

fn int(sim: &Simulator, name: &str) -> i128 {
    sim.with(|d| d.store().int(d.store().id(name).unwrap()).unwrap())
}

/// The SDO downloads to [`NODE`] the sniffer holds (client command specifier 1): every frame
/// of a boot that has returned is queued already, and the node's TPDOs and heartbeats keep
/// coming, so only what is queued is taken.
fn downloads(sniffer: &mut impl CanBus) -> usize {
    let mut count = 0;
    while let Ok(Some(frame)) = sniffer.recv(Duration::ZERO) {
        let request = frame.id() == 0x600 + u16::from(NODE.get());
        if request && frame.data().first().is_some_and(|c| c >> 5 == 1) {
            count += 1;
        }
    }
    count
}

#[test]
fn the_boot_configures_a_tpdo_that_then_arrives_and_a_second_boot_writes_nothing() {
    let bus = InProcessBus::new();
    let mut sniffer = bus.endpoint();
    let (sim, node) = kinco();
    let _nodes = Serving::start(vec![node], bus.endpoint());
    let network = Network::new(bus.endpoint());
    let events = network.subscribe(NODE, 256);

    let plan = kinco_boot::plan(NODE);
    let first = boot_node(&network, &plan, TIMEOUT);
    assert_eq!(first.result, Ok(()));
    assert_eq!((first.written, first.unchanged), (3, 0));
    // Heartbeat 1; TPDO1 8: disable, type, event timer, count 0, 2 entries, count, enable;
    // 6081h 1.
    assert_eq!(downloads(&mut sniffer), 10);
    assert_eq!(int(&sim, "profile_speed"), 1234);

    let expected = [
        &(int(&sim, "statusword") as u16).to_le_bytes()[..],
        &[int(&sim, "modes_of_operation_display") as i8 as u8],
    ]
    .concat();
    let tpdo = std::iter::from_fn(|| events.recv(TIMEOUT).ok().flatten())
        .find_map(|event| match event {
            NetworkEvent::Pdo { number: 1, frame } => Some(frame),
            _ => None,
        })
        .expect("TPDO1 after the boot");
    assert_eq!(tpdo.id(), 0x183);
    assert_eq!(
        tpdo.data(),
        &expected[..],
        "statusword, then the mode display"
    );

    let second = boot_node(&network, &plan, TIMEOUT);
    assert_eq!(second.result, Ok(()));
    assert_eq!((second.written, second.unchanged), (0, 3));
    assert_eq!(
        downloads(&mut sniffer),
        0,
        "a second boot sends no download"
    );
}

#[test]
fn a_pdo_the_node_refuses_ends_the_boot_with_its_step_and_abort_code() {
    use drivebus::canopen::network::boot::{BootError, BootStep};
    use drivebus::canopen::pdo::{MappedObject, PdoKind, PdoSetup};

    let bus = InProcessBus::new();
    let (_sim, node) = kinco();
    let _nodes = Serving::start(vec![node], bus.endpoint());
    let network = Network::new(bus.endpoint());
    let mut plan = kinco_boot::plan(NODE);
    // The Kinco's RPDO1 has no event timer (1400h sub 5): the node refuses that write. (The
    // network file's check refuses it before anything is sent; a raw plan reaches the node.)
    plan.pdos.push(PdoSetup {
        kind: PdoKind::Receive,
        number: 1,
        cob_id: 0x203,
        transmission_type: Some(254),
        inhibit_time: None,
        event_timer: Some(10),
        entries: vec![MappedObject::new(0x6040, 0, 16)],
    });
    let report = boot_node(&network, &plan, TIMEOUT);
    match report.result {
        Err(BootError::Step {
            step: BootStep::Pdo(1),
            error: drivebus::BusError::SdoAbort {
                index, subindex, ..
            },
        }) => assert_eq!((index, subindex), (0x1400, 5)),
        other => panic!("expected RPDO1's event timer refused: {other:?}"),
    }
    assert_eq!(report.written, 2, "the heartbeat and TPDO1, before RPDO1");
}
