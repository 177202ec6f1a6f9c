//! `drivebus::canopen::client::scan` against several simulated nodes on one in-process bus: the nodes
//! that answer are found with their device type and identity, silent node ids are skipped, and
//! the scan of all 127 ids takes about one timeout, not 127.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use drivebus::canopen::can::in_process::InProcessBus;
use drivebus::canopen::client::scan::scan;
use drivebus::canopen::NodeId;
use drivesim::canopen::{Node, NodeConfig};
use drivesim::Simulator;

fn description(name: &str) -> String {
    format!("{}/../descriptions/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn serve(bus: &InProcessBus, sim: Simulator, node: u8, stop: &Arc<AtomicBool>) -> JoinHandle<()> {
    let mut endpoint = bus.endpoint();
    let flag = Arc::clone(stop);
    std::thread::spawn(move || {
        let config = NodeConfig {
            node: NodeId(node),
            heartbeat: None,
        };
        let mut node = Node::new(sim.clone(), config, sim.variant());
        node.run_while(&mut endpoint, || !flag.load(Ordering::Relaxed))
            .unwrap();
    })
}

#[test]
fn scan_finds_every_simulated_node_with_its_identity() {
    let bus = InProcessBus::new();
    let mut client = bus.endpoint();
    let stop = Arc::new(AtomicBool::new(false));
    let swd = Simulator::load(description("ezwheel-swd")).unwrap();
    swd.preset("vendor_id", 0x515).unwrap();
    let lafert = Simulator::load(description("lafert-smartris")).unwrap();
    let kinco = Simulator::load(description("kinco-fd")).unwrap();
    let threads = [
        serve(&bus, swd, 5, &stop),
        serve(&bus, lafert, 17, &stop),
        serve(&bus, kinco, 100, &stop),
    ];
    let nodes: Vec<NodeId> = (1..=127).map(NodeId).collect();
    let timeout = Duration::from_millis(200);
    let started = Instant::now();
    let found = scan(&mut client, &nodes, timeout).unwrap();
    let elapsed = started.elapsed();
    stop.store(true, Ordering::Relaxed);
    for t in threads {
        t.join().unwrap();
    }
    let ids: Vec<u8> = found.iter().map(|n| n.node.get()).collect();
    assert_eq!(ids, [5, 17, 100]);
    assert_eq!(
        found[0].vendor_id,
        Some(0x515),
        "SWD vendor-ID, manual line 1129"
    );
    assert_eq!(found[1].vendor_id, Some(0), "Lafert: unknown, served as 0");
    assert_eq!(
        found[1].product_code, None,
        "Lafert describes no 1018h sub 2"
    );
    assert!(
        elapsed < timeout * 3,
        "127 ids scanned in {elapsed:?}: about one timeout, not one per object or per node"
    );
}

#[test]
fn several_nodes_run_on_one_endpoint_each_answering_for_itself() {
    use drivesim::canopen::nodes;

    let bus = InProcessBus::new();
    let mut client = bus.endpoint();
    let mut endpoint = bus.endpoint();
    let stop = Arc::new(AtomicBool::new(false));
    let flag = Arc::clone(&stop);
    let swd = Simulator::load(description("ezwheel-swd")).unwrap();
    let foreign = Simulator::load(description("ezwheel-swd")).unwrap();
    foreign.preset("vendor_id", 0x1234).unwrap();
    let thread = std::thread::spawn(move || {
        let mut nodes: Vec<Node> = [(swd, 5), (foreign, 6)]
            .into_iter()
            .map(|(sim, id)| {
                let config = NodeConfig {
                    node: NodeId(id),
                    heartbeat: None,
                };
                Node::new(sim.clone(), config, sim.variant())
            })
            .collect();
        nodes::run_while(&mut nodes, &mut endpoint, || !flag.load(Ordering::Relaxed)).unwrap();
    });
    let candidates: Vec<NodeId> = (1..=10).map(NodeId).collect();
    let found = scan(&mut client, &candidates, Duration::from_millis(200)).unwrap();
    stop.store(true, Ordering::Relaxed);
    thread.join().unwrap();
    let vendors: Vec<(u8, Option<u32>)> =
        found.iter().map(|n| (n.node.get(), n.vendor_id)).collect();
    assert_eq!(vendors, [(5, Some(0x515)), (6, Some(0x1234))]);
}
