//! The network manager against python-canopen 2.4.1 as an independent second party: eight
//! LocalNodes (ids 1-8, one relay process, candump stdio) read at once through one `Network`,
//! a missing ninth node timing out alone, an EMCY raised by a write reaching its own node's
//! subscriber only, a node whose heartbeat the manager watches started by NMT for all, and
//! python nodes booted by `network::boot` with a TPDO (python holds the PDO objects it wrote; a
//! second boot writes nothing; a foreign and a missing one left alone).
#![cfg(feature = "canopen")]

mod support;

use std::process::Child;
use std::time::Duration;

use drivebus::canopen::can::candump::CandumpBus;
use drivebus::canopen::network::{Network, NetworkEvent, Subscription};
use drivebus::canopen::nmt::{NmtCommand, NmtState};
use drivebus::canopen::{NodeId, SdoBus};
use drivebus::BusError;
use support::{spawn_peer, stop, STARTUP};

const NODES: u8 = 8;
const TIMEOUT: Duration = Duration::from_secs(2);

/// The relay with LocalNodes 1..=NODES; killed (by PID) when dropped.
struct Peers(Child);

impl Drop for Peers {
    fn drop(&mut self) {
        stop(&mut self.0);
    }
}

/// The relay and a network on it, once every node has booted (each subscriber saw its
/// boot-up).
fn start() -> (
    Peers,
    Network<CandumpBus<std::process::ChildStdin>>,
    Vec<Subscription>,
) {
    let eds = support::peers_dir().join("canopen_peer.eds");
    let ids: Vec<String> = (1..=NODES).map(|id| id.to_string()).collect();
    let args = [eds.display().to_string(), ids.join(",")];
    let mut child = spawn_peer("canopen_relay.py", &args);
    let bus = CandumpBus::from_child(&mut child).expect("piped stdio");
    let network = Network::new(bus);
    let events: Vec<_> = (1..=NODES)
        .map(|id| network.subscribe(NodeId(id), 64))
        .collect();
    let mut peers = Peers(child);
    for subscription in &events {
        if subscription.recv(STARTUP) != Ok(Some(NetworkEvent::BootUp)) {
            let stderr = stop(&mut peers.0);
            panic!(
                "node {} did not boot; run tests/peers/setup-canopen.sh\n{stderr}",
                subscription.node().get()
            );
        }
    }
    (peers, network, events)
}

/// The events of `subscription` until `wanted` came (returned, with those before it), or
/// nothing came for two seconds.
fn events_until(subscription: &Subscription, wanted: NetworkEvent) -> Vec<NetworkEvent> {
    let mut seen = Vec::new();
    while let Ok(Some(event)) = subscription.recv(TIMEOUT) {
        seen.push(event);
        if event == wanted {
            break;
        }
    }
    seen
}

#[test]
fn eight_python_nodes_are_read_at_once_and_a_missing_one_times_out_alone() {
    let (_peers, network, _events) = start();
    let readers: Vec<_> = (1..=NODES + 1)
        .map(|id| {
            let mut sdo = network.node(NodeId(id)).with_timeout(TIMEOUT);
            std::thread::spawn(move || {
                // TPDO1's COB-ID, 180h + the node id (so the answer tells which node gave it),
                // and a string long enough for a segmented upload.
                let mut cob_id = [0u8; 4];
                let mut text = [0u8; 64];
                let result = sdo
                    .upload(NodeId(id), 0x1800, 1, &mut cob_id)
                    .and_then(|_| sdo.upload(NodeId(id), 0x2005, 0, &mut text))
                    .map(|len| (u32::from_le_bytes(cob_id), text[..len].to_vec()));
                (id, result)
            })
        })
        .collect();
    for reader in readers {
        let (id, result) = reader.join().unwrap();
        if id > NODES {
            assert_eq!(
                result,
                Err(BusError::Timeout),
                "node {id} is not on the bus"
            );
        } else {
            let expected = (
                0x180 + u32::from(id),
                b"drivegen segmented transfer peer".to_vec(),
            );
            assert_eq!(result, Ok(expected), "node {id}");
        }
    }
}

#[test]
fn an_emcy_reaches_its_own_node_and_nmt_all_starts_a_watched_node() {
    let (_peers, network, events) = start();
    let mut three = network.node(NodeId(3)).with_timeout(TIMEOUT);
    // The relay answers a write of 2000h with an EMCY of the written code.
    three
        .download(NodeId(3), 0x2000, 0, &0x4321u16.to_le_bytes())
        .unwrap();
    let Ok(Some(NetworkEvent::Emcy(emcy))) = events[2].recv(TIMEOUT) else {
        panic!("node 3 gets its EMCY");
    };
    assert_eq!((emcy.node, emcy.code), (NodeId(3), 0x4321));
    assert_eq!(emcy.manufacturer, [1, 2, 3, 4, 5]);
    assert!(
        events
            .iter()
            .enumerate()
            .all(|(i, e)| i == 2 || e.try_recv().is_none()),
        "no other node gets it"
    );

    // Node 2 produces a heartbeat every 50 ms once reset with 1017h set; the manager watches it.
    let mut two = network.node(NodeId(2)).with_timeout(TIMEOUT);
    two.download(NodeId(2), 0x1017, 0, &50u16.to_le_bytes())
        .unwrap();
    network.monitor_heartbeat(NodeId(2), Duration::from_secs(1));
    network
        .nmt(NmtCommand::ResetCommunication, Some(NodeId(2)))
        .unwrap();
    assert_eq!(
        events_until(&events[1], NetworkEvent::BootUp).last(),
        Some(&NetworkEvent::BootUp)
    );
    network.nmt(NmtCommand::Start, None).unwrap();
    let seen = events_until(&events[1], NetworkEvent::State(NmtState::Operational));
    assert_eq!(
        seen.last(),
        Some(&NetworkEvent::State(NmtState::Operational)),
        "{seen:?}"
    );
    assert_eq!(network.status(NodeId(2)).state, Some(NmtState::Operational));
    assert!(!network.status(NodeId(2)).lost);
}

#[test]
fn python_nodes_are_booted_a_foreign_one_left_alone() {
    use drivebus::canopen::network::boot::{
        boot_all, BootError, BootWrite, ExpectedIdentity, NodeBoot, PdoSetup,
    };
    use drivebus::canopen::pdo::{MappedObject, PdoKind};

    let (_peers, network, events) = start();
    // The EDS's identity: vendor-ID 0DD0h, product code 1.
    let plan = |id: u8, product: u32| NodeBoot {
        node: NodeId(id),
        identity: ExpectedIdentity {
            vendor_id: Some(0x0DD0),
            product_code: Some(product),
            revision: None,
        },
        heartbeat: Some(Duration::from_millis(200)),
        // TPDO1: 2003h (u32), every 100 ms; the EDS gives 1800h sub 1, 2, 5 and 1A00h sub 0-4.
        pdos: vec![PdoSetup {
            kind: PdoKind::Transmit,
            number: 1,
            cob_id: 0x180 + u32::from(id),
            transmission_type: Some(254),
            inhibit_time: None,
            event_timer: Some(100),
            entries: vec![MappedObject::new(0x2003, 0, 32)],
        }],
        writes: vec![BootWrite {
            index: 0x2003,
            subindex: 0,
            data: (0x1000_0000 + u32::from(id)).to_le_bytes().to_vec(),
        }],
        start: true,
    };
    let plans = [plan(1, 1), plan(2, 1), plan(3, 2), plan(NODES + 1, 1)];
    let reports = boot_all(&network, &plans, TIMEOUT);
    let foreign = BootError::Foreign {
        subindex: 2,
        expected: 2,
        found: 1,
    };
    let outcomes = [Ok(()), Ok(()), Err(foreign), Err(BootError::Missing)];
    for ((report, plan), outcome) in reports.iter().zip(&plans).zip(outcomes) {
        assert_eq!(report.node, plan.node);
        assert_eq!(report.result, outcome, "node {}", plan.node.get());
    }
    for (id, expected) in [(1u8, 0x1000_0001u32), (2, 0x1000_0002), (3, 0x1234_5678)] {
        let mut sdo = network.node(NodeId(id)).with_timeout(TIMEOUT);
        let mut out = [0u8; 4];
        sdo.upload(NodeId(id), 0x2003, 0, &mut out).unwrap();
        assert_eq!(u32::from_le_bytes(out), expected, "node {id}");
    }
    // python holds the PDO objects the boot wrote.
    let mut sdo = network.node(NodeId(1)).with_timeout(TIMEOUT);
    for (index, subindex, expected) in [
        (0x1800, 1, 0x181),
        (0x1800, 5, 100),
        (0x1A00, 0, 1),
        (0x1A00, 1, 0x2003_0020),
    ] {
        let mut out = [0u8; 4];
        let len = sdo.upload(NodeId(1), index, subindex, &mut out).unwrap();
        let mut value = [0u8; 4];
        value[..len].copy_from_slice(&out[..len]);
        assert_eq!(
            u32::from_le_bytes(value),
            expected,
            "{index:04X}h sub {subindex}"
        );
    }
    // A second boot finds every item in place and writes nothing.
    let again = boot_all(&network, &plans[..2], TIMEOUT);
    for report in &again {
        assert_eq!(report.result, Ok(()));
        assert_eq!(
            (report.written, report.unchanged),
            (0, 3),
            "node {}",
            report.node.get()
        );
    }
    // Node 1 runs: the heartbeat it was given reports it operational.
    let seen = events_until(&events[0], NetworkEvent::State(NmtState::Operational));
    assert_eq!(
        seen.last(),
        Some(&NetworkEvent::State(NmtState::Operational)),
        "{seen:?}"
    );
}
