//! Several simulated nodes on one CAN bus, as drives share a real one: every node sees every
//! frame the master sends and every frame another node sends, and answers for its own node id
//! only. `drivegen sim` serves a whole bus this way, and a bus scan finds each node.

use std::time::{Duration, Instant};

use drivebus::canopen::{CanBus, CanFrame};
use drivebus::BusError;

use super::Node;

/// How long one turn waits for a frame before the nodes' timers run.
const TURN: Duration = Duration::from_millis(10);

/// Runs `nodes` on `bus` until the bus fails (e.g. the candump stream ends).
pub fn run<B: CanBus>(nodes: &mut [Node], bus: &mut B) -> Result<(), BusError> {
    run_while(nodes, bus, || true)
}

/// Runs `nodes` on `bus` while `keep_running` says so (checked every 10 ms): each boots, then
/// handles the frames it receives and sends what is due.
pub fn run_while<B: CanBus>(
    nodes: &mut [Node],
    bus: &mut B,
    keep_running: impl Fn() -> bool,
) -> Result<(), BusError> {
    let epoch = Instant::now();
    let boot_ups: Vec<CanFrame> = nodes
        .iter_mut()
        .filter_map(|n| n.boot(epoch.elapsed()))
        .collect();
    send_all(nodes, bus, boot_ups, epoch)?;
    while keep_running() {
        let received = bus.recv(TURN)?;
        let now = epoch.elapsed();
        let sent: Vec<CanFrame> = nodes
            .iter_mut()
            .flat_map(|node| node.step(received.as_ref(), now))
            .collect();
        send_all(nodes, bus, sent, epoch)?;
    }
    Ok(())
}

/// Sends `frames`, and hands each to the other nodes as the bus would; their answers go out in
/// turn. A node never answers its own frames, and nodes answer only masters' requests, so this
/// ends.
fn send_all<B: CanBus>(
    nodes: &mut [Node],
    bus: &mut B,
    frames: Vec<CanFrame>,
    epoch: Instant,
) -> Result<(), BusError> {
    let mut pending = frames;
    while !pending.is_empty() {
        let mut answers = Vec::new();
        for frame in &pending {
            bus.send(frame)?;
            if nodes.len() > 1 {
                let now = epoch.elapsed();
                answers.extend(nodes.iter_mut().flat_map(|node| node.handle(frame, now)));
            }
        }
        pending = answers;
    }
    Ok(())
}
