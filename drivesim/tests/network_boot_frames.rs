//! Issue 31's boot benchmark, frames and wire time: one simulated Kinco booted by
//! `network::boot` (probe, vendor-ID, heartbeat, TPDO1, one boot parameter, start) and by python
//! canopen 2.4.1 doing the same steps (`tests/peers/network_boot_master.py`). Only the boot's
//! own frames count: SDO requests and answers and NMT (not the heartbeats or TPDOs the node
//! then sends). The counts follow from the steps, so they are asserted; the table is printed
//! (`--nocapture`) for docs/benchmarks.md.

mod network_support;

use std::process::{Command, Stdio};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use drivebus::canopen::can::candump::CandumpBus;
use drivebus::canopen::can::in_process::InProcessBus;
use drivebus::canopen::network::boot::{boot_node, ExpectedIdentity, NodeBoot};
use drivebus::canopen::network::Network;
use drivebus::canopen::{CanBus, CanFrame, NodeId};
use drivebus::BusError;
use drivesim::canopen::{Node, NodeConfig};
use drivesim::Simulator;
use network_support::{kinco_boot, Serving};
use peer_support::{python, workspace_root, SETUP_HINT};

const NODE: NodeId = NodeId(3);
const TIMEOUT: Duration = Duration::from_millis(1000);
/// The bit rate the wire time is given for.
const BITRATE: u32 = 500_000;

fn kinco() -> Simulator {
    Simulator::load(workspace_root().join("descriptions/kinco-fd")).unwrap()
}

fn int(sim: &Simulator, name: &str) -> u32 {
    sim.with(|d| d.store().int(d.store().id(name).unwrap()).unwrap()) as u32
}

/// The boot's own frames: NMT, and SDO to and from [`NODE`].
fn boot_frame(frame: &CanFrame) -> bool {
    let node = u16::from(NODE.get());
    [0x000, 0x580 + node, 0x600 + node].contains(&frame.id())
}

/// Bits of a base-format data frame on the wire without stuffing: 47 + 8 per data byte
/// (SOF, identifier, control, CRC, ACK, EOF and the interframe space).
fn wire_bits(frames: &[CanFrame]) -> u64 {
    frames.iter().map(|f| 47 + 8 * f.data().len() as u64).sum()
}

/// The Kinco boot the PDO tests run, with the node's vendor-ID checked.
fn plan(sim: &Simulator) -> NodeBoot {
    NodeBoot {
        identity: ExpectedIdentity {
            vendor_id: Some(int(sim, "vendor_id")),
            // The Kinco describes no product code.
            ..ExpectedIdentity::default()
        },
        ..kinco_boot::plan(NODE)
    }
}

/// The boot frames the sniffer holds. Every SDO frame of a boot that returned is queued; the
/// NMT start the router sends within a poll interval (1 ms): 100 ms is ample.
fn sniffed(sniffer: &mut impl CanBus) -> Vec<CanFrame> {
    std::thread::sleep(Duration::from_millis(100));
    std::iter::from_fn(|| sniffer.recv(Duration::ZERO).ok().flatten())
        .filter(boot_frame)
        .collect()
}

/// drivebus's first and second boot of a fresh node.
fn drivebus_boots() -> (Vec<CanFrame>, Vec<CanFrame>) {
    let bus = InProcessBus::new();
    let mut sniffer = bus.endpoint();
    let sim = kinco();
    let config = NodeConfig {
        node: NODE,
        heartbeat: None,
    };
    let _nodes = Serving::start(vec![Node::new(sim.clone(), config, None)], bus.endpoint());
    let network = Network::new(bus.endpoint());
    let plan = plan(&sim);
    assert_eq!(boot_node(&network, &plan, TIMEOUT).result, Ok(()));
    let first = sniffed(&mut sniffer);
    assert_eq!(boot_node(&network, &plan, TIMEOUT).result, Ok(()));
    (first, sniffed(&mut sniffer))
}

/// A bus that keeps every frame it carries.
struct Recording<B> {
    bus: B,
    frames: Arc<Mutex<Vec<CanFrame>>>,
}

impl<B: CanBus> CanBus for Recording<B> {
    fn send(&mut self, frame: &CanFrame) -> Result<(), BusError> {
        self.frames.lock().unwrap().push(*frame);
        self.bus.send(frame)
    }

    fn recv(&mut self, timeout: Duration) -> Result<Option<CanFrame>, BusError> {
        let frame = self.bus.recv(timeout)?;
        self.frames.lock().unwrap().extend(frame);
        Ok(frame)
    }
}

/// python canopen's boot of a fresh node.
fn python_boot() -> Vec<CanFrame> {
    let sim = kinco();
    let dir = std::env::temp_dir().join(format!("network-boot-frames-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let eds = dir.join("kinco-fd.eds");
    let described = drivegen::check(&workspace_root().join("descriptions/kinco-fd")).device;
    std::fs::write(&eds, drivegen::eds::export(&described.unwrap())).unwrap();
    let mut child = Command::new(python())
        .arg(workspace_root().join("tests/peers/network_boot_master.py"))
        .arg(&eds)
        .arg(NODE.get().to_string())
        .arg(int(&sim, "vendor_id").to_string())
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("cannot start python ({e}); {SETUP_HINT}"));
    let frames = Arc::new(Mutex::new(Vec::new()));
    let mut bus = Recording {
        bus: CandumpBus::from_child(&mut child).unwrap(),
        frames: Arc::clone(&frames),
    };
    let node = std::thread::spawn(move || {
        let config = NodeConfig {
            node: NODE,
            heartbeat: None,
        };
        // Runs until the script's stdout closes.
        let _ = Node::new(sim.clone(), config, None).run(&mut bus);
    });
    let output = child.wait_with_output().unwrap();
    node.join().unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    assert!(
        output.status.success(),
        "python canopen's boot failed:\n{}\n{SETUP_HINT}",
        String::from_utf8_lossy(&output.stderr)
    );
    let recorded = frames.lock().unwrap();
    recorded.iter().copied().filter(boot_frame).collect()
}

#[test]
fn a_boot_costs_the_frames_its_steps_take_beside_python_canopen() {
    let (first, second) = drivebus_boots();
    let python = python_boot();
    let row = |name: &str, frames: &[CanFrame]| {
        let bits = wire_bits(frames);
        let us = bits * 1_000_000 / u64::from(BITRATE);
        println!("| {name} | {} | {bits} | {us} µs |", frames.len());
    };
    println!("| boot (one Kinco node) | frames | bits | wire time at 500 kbit/s |");
    println!("| --- | --- | --- | --- |");
    row("drivebus, first boot", &first);
    row("drivebus, second boot (nothing differs)", &second);
    row("python canopen 2.4.1", &python);
    // python: 2 reads (1000h, 1018h sub 1), 1 + 8 + 1 writes, a request and an answer each,
    // and NMT start.
    assert_eq!(python.len(), 2 * 12 + 1, "python canopen's steps");
    // drivebus reads every configured object before writing it: heartbeat 1; TPDO1 3 (COB-ID
    // and type hold the Kinco's defaults, the event timer differs and ends the check); 6081h 1.
    assert_eq!(first.len(), 2 * (12 + 5) + 1, "drivebus's first boot");
    // The second boot only reads: 2 identity reads, then heartbeat 1, TPDO1 6 (COB-ID, type,
    // timer, count, 2 entries), 6081h 1, all holding their values.
    assert_eq!(second.len(), 2 * 10 + 1, "drivebus's second boot");
}
