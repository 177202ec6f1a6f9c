//! Network boot over the network manager against simulated nodes on one bus: four nodes booted
//! at once (identity checked, heartbeat set and watched, boot parameters written, started), a
//! missing node and one with a foreign identity reported and left alone, a node that aborts a
//! boot parameter reported with the step and abort code; booting again changes nothing; and
//! the async driver does the same for one node.

mod network_support;

use std::time::Duration;

use drivebus::asynch::TokioTimer;
use drivebus::canopen::can::in_process::InProcessBus;
use drivebus::canopen::network::boot::{
    boot_all, boot_node_async, BootError, BootStep, BootWrite, ExpectedIdentity, NodeBoot,
};
use drivebus::canopen::network::{AsyncNetwork, Network, NetworkEvent};
use drivebus::canopen::nmt::NmtState;
use drivebus::canopen::sdo::AbortCode;
use drivebus::canopen::{AsyncSdoBus, CanBus, NodeId, SdoBus};
use drivebus::BusError;
use drivesim::canopen::{Node, NodeConfig};
use drivesim::Simulator;
use network_support::Serving;

const FIXTURE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/fixtures/network_node.toml"
);
const TIMEOUT: Duration = Duration::from_millis(1000);
const VENDOR: u32 = 0x0000_0DD0;

/// Nodes `ids`, each of vendor [`VENDOR`] and product code 7, except node 3 (product 8).
fn simulated(ids: &[u8]) -> Vec<Node> {
    let device = drivegen::check(FIXTURE.as_ref()).device.unwrap();
    ids.iter()
        .map(|&id| {
            let sim = Simulator::new(device.clone());
            sim.preset("vendor_id", i128::from(VENDOR)).unwrap();
            sim.preset("product_code", if id == 3 { 8 } else { 7 })
                .unwrap();
            sim.preset("revision_number", 1).unwrap();
            let config = NodeConfig {
                node: NodeId(id),
                heartbeat: None,
            };
            Node::new(sim.clone(), config, sim.variant())
        })
        .collect()
}

/// Expects vendor [`VENDOR`], product 7; heartbeat 200 ms (watched for 450 ms); setpoint
/// (2000h) = `setpoint`.
fn plan(id: u8, setpoint: i16) -> NodeBoot {
    NodeBoot {
        node: NodeId(id),
        identity: ExpectedIdentity {
            vendor_id: Some(VENDOR),
            product_code: Some(7),
            revision: None,
        },
        heartbeat: Some(Duration::from_millis(200)),
        pdos: vec![],
        writes: vec![BootWrite {
            index: 0x2000,
            subindex: 0,
            data: setpoint.to_le_bytes().to_vec(),
        }],
        start: true,
    }
}

fn setpoint(network: &Network<impl CanBus>, id: u8) -> i16 {
    let mut out = [0u8; 2];
    let mut sdo = network.node(NodeId(id)).with_timeout(TIMEOUT);
    sdo.upload(NodeId(id), 0x2000, 0, &mut out).unwrap();
    i16::from_le_bytes(out)
}

#[test]
fn a_network_boots_leaving_missing_foreign_and_refusing_nodes_reported() {
    let bus = InProcessBus::new();
    let _nodes = Serving::start(simulated(&[1, 2, 3, 4]), bus.endpoint());
    let network = Network::new(bus.endpoint());
    let events = network.subscribe(NodeId(1), 64);
    let mut refusing = plan(4, 40);
    // 2001h is read-only: the node aborts the second boot parameter.
    refusing.writes.push(BootWrite {
        index: 0x2001,
        subindex: 0,
        data: vec![1, 0],
    });
    let plans = [plan(1, 10), plan(2, 20), plan(3, 30), refusing, plan(9, 90)];
    let reports = boot_all(&network, &plans, TIMEOUT);
    let results: Vec<_> = reports
        .iter()
        .map(|r| (r.node.get(), r.result.clone()))
        .collect();
    assert_eq!(
        results,
        [
            (1, Ok(())),
            (2, Ok(())),
            (
                3,
                Err(BootError::Foreign {
                    subindex: 2,
                    expected: 7,
                    found: 8
                })
            ),
            (
                4,
                Err(BootError::Step {
                    step: BootStep::Write(1),
                    error: BusError::SdoAbort {
                        index: 0x2001,
                        subindex: 0,
                        code: AbortCode::ReadOnly
                    }
                })
            ),
            (9, Err(BootError::Missing)),
        ]
    );
    assert_eq!([setpoint(&network, 1), setpoint(&network, 2)], [10, 20]);
    assert_eq!(setpoint(&network, 3), 100, "a foreign node is left alone");
    assert_eq!(setpoint(&network, 4), 40, "written before the refused one");

    // Node 1 was started and produces its heartbeat, which the manager now watches.
    let mut seen = Vec::new();
    while let Ok(Some(event)) = events.recv(TIMEOUT) {
        seen.push(event);
        if event == NetworkEvent::State(NmtState::Operational) {
            break;
        }
    }
    assert_eq!(
        seen.last(),
        Some(&NetworkEvent::State(NmtState::Operational)),
        "{seen:?}"
    );
    assert!(!network.status(NodeId(1)).lost);
    assert_ne!(
        network.status(NodeId(3)).state,
        Some(NmtState::Operational),
        "the foreign node was not started"
    );

    // Again: the same results, the same values, and nothing written where the node holds it.
    let again = boot_all(&network, &plans, TIMEOUT);
    let outcome = |r: &drivebus::canopen::network::boot::BootReport| (r.node, r.result.clone());
    assert_eq!(
        again.iter().map(outcome).collect::<Vec<_>>(),
        reports.iter().map(outcome).collect::<Vec<_>>()
    );
    let counts: Vec<_> = [&reports[0], &again[0], &again[3]]
        .iter()
        .map(|r| (r.written, r.unchanged))
        .collect();
    assert_eq!(
        counts,
        [(2, 0), (0, 2), (0, 2)],
        "node 1 written then unchanged; node 4 unchanged up to its refused write (tried again)"
    );
    assert_eq!([setpoint(&network, 1), setpoint(&network, 2)], [10, 20]);
}

#[tokio::test]
async fn the_async_driver_boots_a_node() {
    let bus = drivebus::canopen::can::async_in_process::AsyncInProcessBus::new();
    let (network, mut router) = AsyncNetwork::new(bus.endpoint(), TokioTimer);
    let relay = relay_to_simulated(&bus, simulated(&[5]));
    let plan = plan(5, 55);
    let work = async {
        let report = boot_node_async(&network, &plan, TIMEOUT).await;
        let mut out = [0u8; 2];
        let mut sdo = network.node(NodeId(5)).with_timeout(TIMEOUT);
        let read = AsyncSdoBus::upload(&mut sdo, NodeId(5), 0x2000, 0, &mut out).await;
        network.close();
        (report, read.map(|_| i16::from_le_bytes(out)))
    };
    let (routed, (report, setpoint)) = tokio::join!(router.run(), work);
    routed.unwrap();
    drop(relay);
    assert_eq!(report.result, Ok(()));
    assert_eq!(
        report.device_type,
        Some(0),
        "the fixture describes no device type value"
    );
    assert_eq!(setpoint, Ok(55));
}

/// Serves `nodes` on an endpoint of an async in-process bus from a thread that polls it (every
/// 200 µs when idle): frames from the bus are handed to the nodes, their answers sent back.
fn relay_to_simulated(
    bus: &drivebus::canopen::can::async_in_process::AsyncInProcessBus,
    mut nodes: Vec<Node>,
) -> Serving {
    use drivebus::canopen::can::AsyncCanBus;
    use std::future::Future;
    use std::task::{Context, Poll, Waker};

    let mut endpoint = bus.endpoint();
    Serving::spawn(move |running| {
        let epoch = std::time::Instant::now();
        let mut cx = Context::from_waker(Waker::noop());
        let boot_ups: Vec<_> = nodes
            .iter_mut()
            .filter_map(|n| n.boot(epoch.elapsed()))
            .collect();
        for frame in boot_ups {
            let _ = endpoint.try_send(&frame);
        }
        while running() {
            let received = match std::pin::pin!(endpoint.recv()).poll(&mut cx) {
                Poll::Ready(Ok(frame)) => Some(frame),
                Poll::Ready(Err(_)) => return,
                Poll::Pending => None,
            };
            let now = epoch.elapsed();
            let sent: Vec<_> = nodes
                .iter_mut()
                .flat_map(|node| node.step(received.as_ref(), now))
                .collect();
            for frame in sent {
                let _ = endpoint.try_send(&frame);
            }
            if received.is_none() {
                std::thread::sleep(Duration::from_micros(200));
            }
        }
    })
}
