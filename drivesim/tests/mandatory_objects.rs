//! Every shipped CANopen description's simulator answers the CiA 301 mandatory objects a master
//! reads first (python canopen, lely, CiA 302 boot-up): 1000h, 1001h and 1018h sub 0 and 1.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;

use drivebus::canopen::can::in_process::InProcessBus;
use drivebus::canopen::client::BlockingSdo;
use drivebus::canopen::{NodeId, SdoBus};
use drivesim::canopen::{Node, NodeConfig};
use drivesim::Simulator;

const CANOPEN_DESCRIPTIONS: &[&str] = &["ezwheel-swd", "kinco-fd", "lafert-smartris"];
const MANDATORY: &[(u16, u8, usize)] = &[
    (0x1000, 0, 4),
    (0x1001, 0, 1),
    (0x1018, 0, 1),
    (0x1018, 1, 4),
];

#[test]
fn every_canopen_description_answers_the_mandatory_objects() {
    for name in CANOPEN_DESCRIPTIONS {
        let path = format!("{}/../descriptions/{name}", env!("CARGO_MANIFEST_DIR"));
        let sim = Simulator::load(&path).unwrap();
        let bus = InProcessBus::new();
        let mut sdo = BlockingSdo::new(bus.endpoint()).with_timeout(Duration::from_millis(300));
        let mut endpoint = bus.endpoint();
        let stop = Arc::new(AtomicBool::new(false));
        let flag = Arc::clone(&stop);
        let thread = std::thread::spawn(move || {
            let config = NodeConfig {
                node: NodeId(3),
                heartbeat: None,
            };
            let mut node = Node::new(sim.clone(), config, sim.variant());
            node.run_while(&mut endpoint, || !flag.load(Ordering::Relaxed))
                .unwrap();
        });
        for &(index, sub, len) in MANDATORY {
            let mut buf = [0u8; 8];
            let read = sdo.upload(NodeId(3), index, sub, &mut buf);
            assert_eq!(read.ok(), Some(len), "{name}: {index:04X}h sub {sub}");
        }
        stop.store(true, Ordering::Relaxed);
        thread.join().unwrap();
    }
}
