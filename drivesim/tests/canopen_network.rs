//! The CANopen network manager against simulated nodes sharing one bus: 32 nodes read at once
//! (blocking threads on an in-process bus, async futures over SLCAN on TCP), a missing node that
//! times out alone, a node whose heartbeat stops and comes back, EMCY and PDO dispatch to the
//! right node, and NMT for all nodes.

mod network_support;

use std::future::Future;
use std::net::TcpListener;
use std::pin::Pin;
use std::task::Poll;
use std::time::Duration;

use drivebus::asynch::TokioTimer;
use drivebus::canopen::can::async_slcan::AsyncSlcanBus;
use drivebus::canopen::can::in_process::InProcessBus;
use drivebus::canopen::can::slcan::SlcanBus;
use drivebus::canopen::network::{AsyncNetwork, Network, NetworkEvent, Subscription};
use drivebus::canopen::nmt::{NmtCommand, NmtState};
use drivebus::canopen::{AsyncSdoBus, CanBus, CanFrame, NodeId, SdoBus};
use drivebus::BusError;
use drivesim::canopen::{Node, NodeConfig};
use drivesim::Simulator;
use network_support::Serving;

const FIXTURE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/fixtures/enforcement.toml"
);

/// Generous: the simulated nodes share two cores with parallel builds.
const TIMEOUT: Duration = Duration::from_millis(1000);
/// Node 33 is not on the bus.
const MISSING: NodeId = NodeId(33);

/// `count` nodes 1..=count of the fixture, each measuring ten times its node id (2001h), so a
/// value read tells which node answered.
fn simulated_nodes(count: u8, heartbeat: Option<Duration>) -> Vec<Node> {
    let device = drivegen::check(FIXTURE.as_ref()).device.unwrap();
    (1..=count)
        .map(|id| {
            let sim = Simulator::new(device.clone());
            sim.preset("measured", i128::from(id) * 10).unwrap();
            let config = NodeConfig {
                node: NodeId(id),
                heartbeat,
            };
            Node::new(sim.clone(), config, sim.variant())
        })
        .collect()
}

fn measured(result: Result<usize, BusError>, out: [u8; 2]) -> Result<u16, BusError> {
    result.map(|len| {
        assert_eq!(len, 2);
        u16::from_le_bytes(out)
    })
}

#[test]
fn thirty_two_nodes_are_read_at_once_and_a_missing_node_times_out_alone() {
    let bus = InProcessBus::new();
    let _nodes = Serving::start(simulated_nodes(32, None), bus.endpoint());
    let network = Network::new(bus.endpoint());
    let readers: Vec<_> = (1..=33u8)
        .map(|id| {
            let mut sdo = network.node(NodeId(id)).with_timeout(TIMEOUT);
            std::thread::spawn(move || {
                let mut out = [0u8; 2];
                let result = sdo.upload(NodeId(id), 0x2001, 0, &mut out);
                (id, measured(result, out))
            })
        })
        .collect();
    for reader in readers {
        let (id, value) = reader.join().unwrap();
        if id == MISSING.get() {
            assert_eq!(value, Err(BusError::Timeout), "node {id}");
        } else {
            assert_eq!(value, Ok(u16::from(id) * 10), "node {id}");
        }
    }
    assert_eq!(network.stale_sdo_responses(), 0);
}

#[test]
fn a_node_handle_runs_a_generated_style_link_and_refuses_other_nodes() {
    let bus = InProcessBus::new();
    let _nodes = Serving::start(simulated_nodes(2, None), bus.endpoint());
    let network = Network::new(bus.endpoint());
    let mut sdo = network.node(NodeId(2)).with_timeout(TIMEOUT);
    sdo.download(NodeId(2), 0x2000, 0, &(-1234i16).to_le_bytes())
        .unwrap();
    let mut out = [0u8; 2];
    assert_eq!(sdo.upload(NodeId(2), 0x2000, 0, &mut out), Ok(2));
    assert_eq!(i16::from_le_bytes(out), -1234);
    assert!(matches!(
        sdo.upload(NodeId(1), 0x2000, 0, &mut out),
        Err(BusError::Unsupported(_))
    ));
    let mut one = network.node(NodeId(1)).with_timeout(TIMEOUT);
    assert_eq!(one.upload(NodeId(1), 0x2000, 0, &mut out), Ok(2));
    assert_eq!(i16::from_le_bytes(out), 100, "node 1 kept its own value");
}

/// Every future of `futures` to its end, polled together on the current task.
async fn join_all<T>(mut futures: Vec<Pin<Box<dyn Future<Output = T> + '_>>>) -> Vec<T> {
    let mut done: Vec<Option<T>> = futures.iter().map(|_| None).collect();
    std::future::poll_fn(|cx| {
        for (future, slot) in futures.iter_mut().zip(done.iter_mut()) {
            if slot.is_none() {
                if let Poll::Ready(value) = future.as_mut().poll(cx) {
                    *slot = Some(value);
                }
            }
        }
        if done.iter().all(Option::is_some) {
            Poll::Ready(done.iter_mut().map(|d| d.take().unwrap()).collect())
        } else {
            Poll::Pending
        }
    })
    .await
}

#[tokio::test]
async fn thirty_two_nodes_are_read_at_once_over_slcan_by_the_async_manager() {
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let address = listener.local_addr().unwrap();
    let server = std::thread::spawn(move || {
        let (stream, _) = listener.accept().unwrap();
        Serving::start(simulated_nodes(32, None), SlcanBus::tcp(stream).unwrap())
    });
    let bus = AsyncSlcanBus::connect(address).await.unwrap();
    let (network, mut router) = AsyncNetwork::new(bus, TokioTimer);
    let _nodes = server.join().unwrap();
    let work = async {
        let reads = (1..=33u8)
            .map(|id| {
                let mut sdo = network.node(NodeId(id)).with_timeout(TIMEOUT);
                Box::pin(async move {
                    let mut out = [0u8; 2];
                    let result = sdo.upload(NodeId(id), 0x2001, 0, &mut out).await;
                    (id, measured(result, out))
                }) as Pin<Box<dyn Future<Output = _>>>
            })
            .collect();
        let results = join_all(reads).await;
        network.close();
        results
    };
    let (routed, results) = tokio::join!(router.run(), work);
    routed.unwrap();
    for (id, value) in results {
        if id == MISSING.get() {
            assert_eq!(value, Err(BusError::Timeout), "node {id}");
        } else {
            assert_eq!(value, Ok(u16::from(id) * 10), "node {id}");
        }
    }
}

/// The events of `subscription` until `wanted` came (returned, with those before it), or three
/// seconds passed without any event.
fn events_until(subscription: &Subscription, wanted: NetworkEvent) -> Vec<NetworkEvent> {
    let mut seen = Vec::new();
    while let Ok(Some(event)) = subscription.recv(Duration::from_secs(3)) {
        seen.push(event);
        if event == wanted {
            break;
        }
    }
    seen
}

#[test]
fn a_node_whose_heartbeat_stops_is_lost_then_back() {
    let bus = InProcessBus::new();
    let node = NodeId(1);
    let heartbeat = Some(Duration::from_millis(50));
    let network = Network::new(bus.endpoint());
    let events = network.subscribe(node, 64);
    // A second of silence: far beyond a stall of the simulated node's thread on a loaded machine.
    network.monitor_heartbeat(node, Duration::from_secs(1));
    let serving = Serving::start(simulated_nodes(1, heartbeat), bus.endpoint());
    assert_eq!(
        events.recv(TIMEOUT),
        Ok(Some(NetworkEvent::BootUp)),
        "the node boots"
    );
    drop(serving);
    let lost = events_until(&events, NetworkEvent::Lost);
    assert_eq!(lost.last(), Some(&NetworkEvent::Lost), "{lost:?}");
    assert!(network.status(node).lost);
    let _serving = Serving::start(simulated_nodes(1, heartbeat), bus.endpoint());
    let back = events_until(&events, NetworkEvent::BootUp);
    assert_eq!(
        back,
        [NetworkEvent::Back, NetworkEvent::BootUp],
        "the boot-up ends the silence, and is reported"
    );
    assert!(!network.status(node).lost);
    assert_eq!(events.dropped(), 0);
}

#[test]
fn pdos_and_emcys_reach_their_own_node_subscriber() {
    let bus = InProcessBus::new();
    let network = Network::new(bus.endpoint());
    let (seven, eight) = (
        network.subscribe(NodeId(7), 8),
        network.subscribe(NodeId(8), 8),
    );
    let mut device = bus.endpoint();
    let tpdo1 = CanFrame::new(0x187, &[0x34, 0x12]).unwrap();
    let emcy = CanFrame::new(0x088, &[0x10, 0x23, 0x01, 0, 0, 0, 0, 0]).unwrap();
    let tpdo3_of_9 = CanFrame::new(0x389, &[1]).unwrap();
    for frame in [tpdo3_of_9, tpdo1, emcy] {
        device.send(&frame).unwrap();
    }
    assert_eq!(
        seven.recv(TIMEOUT),
        Ok(Some(NetworkEvent::Pdo {
            number: 1,
            frame: tpdo1
        }))
    );
    let Ok(Some(NetworkEvent::Emcy(received))) = eight.recv(TIMEOUT) else {
        panic!("node 8 gets its EMCY");
    };
    assert_eq!((received.node, received.code), (NodeId(8), 0x2310));
    assert_eq!(network.status(NodeId(8)).last_emcy, Some(received));
    assert_eq!(seven.try_recv(), None, "nothing else for node 7");
    assert_eq!(eight.try_recv(), None, "nothing else for node 8");
}

#[test]
fn a_subscriber_that_falls_behind_loses_its_oldest_events_and_the_router_goes_on() {
    let bus = InProcessBus::new();
    let network = Network::new(bus.endpoint());
    let slow = network.subscribe(NodeId(7), 4);
    let mut device = bus.endpoint();
    for value in 0..10u8 {
        device
            .send(&CanFrame::new(0x187, &[value]).unwrap())
            .unwrap();
    }
    // The router is not held up: a node's SDO answer after the flood still gets through.
    let (_nodes, mut sdo) = (
        Serving::start(simulated_nodes(1, None), bus.endpoint()),
        network.node(NodeId(1)).with_timeout(TIMEOUT),
    );
    let mut out = [0u8; 2];
    assert_eq!(sdo.upload(NodeId(1), 0x2001, 0, &mut out), Ok(2));
    assert_eq!(slow.dropped(), 6);
    let kept: Vec<u8> = std::iter::from_fn(|| slow.try_recv())
        .map(|event| match event {
            NetworkEvent::Pdo { frame, .. } => frame.data()[0],
            other => panic!("{other:?}"),
        })
        .collect();
    assert_eq!(kept, [6, 7, 8, 9]);
}

#[test]
fn nmt_start_all_starts_every_node() {
    let bus = InProcessBus::new();
    let network = Network::new(bus.endpoint());
    let subscribers: Vec<_> = (1..=3)
        .map(|id| network.subscribe(NodeId(id), 16))
        .collect();
    let _nodes = Serving::start(
        simulated_nodes(3, Some(Duration::from_millis(20))),
        bus.endpoint(),
    );
    for events in &subscribers {
        assert_eq!(events.recv(TIMEOUT), Ok(Some(NetworkEvent::BootUp)));
    }
    network.nmt(NmtCommand::Start, None).unwrap();
    for events in &subscribers {
        let seen = events_until(events, NetworkEvent::State(NmtState::Operational));
        assert_eq!(
            seen.last(),
            Some(&NetworkEvent::State(NmtState::Operational)),
            "node {}: {seen:?}",
            events.node().get()
        );
        assert_eq!(
            network.status(events.node()).state,
            Some(NmtState::Operational)
        );
    }
}

#[test]
fn sync_is_produced_at_the_set_period_and_stops() {
    let bus = InProcessBus::new();
    let network = Network::new(bus.endpoint());
    let mut listener = bus.endpoint();
    network.set_sync(Some(Duration::from_millis(10)));
    let mut syncs = 0;
    while syncs < 5 {
        let frame = listener.recv(TIMEOUT).unwrap().expect("a SYNC");
        assert_eq!((frame.id(), frame.dlc()), (0x080, 0));
        syncs += 1;
    }
    network.set_sync(None);
    // Drain what was on its way, then silence.
    while listener.recv(Duration::from_millis(50)).unwrap().is_some() {}
    assert_eq!(listener.recv(Duration::from_millis(100)).unwrap(), None);
}

#[test]
fn handles_answer_closed_after_the_network_is_shut_down() {
    let bus = InProcessBus::new();
    let network = Network::new(bus.endpoint());
    let mut sdo = network.node(NodeId(1));
    let events = network.subscribe(NodeId(1), 4);
    network.shutdown().unwrap();
    let mut out = [0u8; 2];
    assert_eq!(
        sdo.upload(NodeId(1), 0x2001, 0, &mut out),
        Err(BusError::Closed)
    );
    assert_eq!(events.recv(TIMEOUT), Err(BusError::Closed));
}
