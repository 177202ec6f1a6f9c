//! python canopen 2.4.1 as an independent SDO master (`tests/peers/swd_sdo_master.py` at the workspace root): it loads
//! the EDS drivegen exports from the SWD description and reads every readable object of the
//! simulated SWD, each value checked against the EDS type and default. The simulated node runs
//! here on a candump stdio relay to the python process, which is stopped by its PID. A missing
//! peer fails the test: run `tests/peers/setup.sh`.

use std::io::Read;
use std::path::Path;
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use drivebus::canopen::can::candump::CandumpBus;
use drivebus::canopen::NodeId;
use drivesim::canopen::{Node, NodeConfig};
use drivesim::Simulator;
use peer_support::{python, Process};

const DESCRIPTION: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../descriptions/ezwheel-swd"
);

#[test]
fn python_canopen_reads_every_readable_object_through_the_exported_eds() {
    let checked = drivegen::check(Path::new(DESCRIPTION));
    let device = checked.device.expect("the SWD description is valid");
    let dir = std::env::temp_dir().join(format!("swd-eds-peer-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let eds = dir.join("ezwheel-swd.eds");
    std::fs::write(&eds, drivegen::eds::export(&device)).unwrap();

    let mut child = Command::new(python())
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/peers/swd_sdo_master.py"))
        .arg(&eds)
        .arg("0x10")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("cannot start python ({e}); run tests/peers/setup.sh"));
    let mut stderr = child.stderr.take().unwrap();
    let mut bus = CandumpBus::from_child(&mut child).unwrap();
    // Killed by its PID and reaped when the test ends, whatever happens.
    let mut peer = Process::new(child);

    let sim = Simulator::load(DESCRIPTION).unwrap();
    let stop = Arc::new(AtomicBool::new(false));
    let running = Arc::clone(&stop);
    let node = std::thread::spawn(move || {
        let config = NodeConfig {
            node: NodeId(0x10),
            heartbeat: None,
        };
        let mut node = Node::new(sim.clone(), config, sim.variant());
        // The relay ends when the peer exits (its stdout closes): that error ends the node too.
        let _ = node.run_while(&mut bus, || !running.load(Ordering::Relaxed));
    });

    let deadline = Instant::now() + Duration::from_secs(120);
    let status = loop {
        if let Some(status) = peer.child_mut().try_wait().unwrap() {
            break Some(status);
        }
        if Instant::now() > deadline {
            break None;
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    stop.store(true, Ordering::Relaxed);
    node.join().unwrap();
    let mut report = String::new();
    stderr.read_to_string(&mut report).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    let status = status.unwrap_or_else(|| panic!("python canopen timed out:\n{report}"));
    assert!(
        status.success() && report.contains("ok: "),
        "python canopen master failed ({status}):\n{report}"
    );
    // Every readable object: the description has 866 parameters; the write-only ones and the
    // derived PDO objects change the count a little, so only a lower bound is fixed here.
    let read: usize = report
        .rsplit("ok: ")
        .next()
        .and_then(|r| r.split_whitespace().next())
        .and_then(|n| n.parse().ok())
        .unwrap();
    assert!(read > 850, "{report}");
    eprintln!("{report}");
}
