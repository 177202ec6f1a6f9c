//! Simulated nodes served on any CAN bus from their own thread, until stopped: the in-process
//! test double ([`InProcessNode`](super::InProcessNode)) and the benchmarks' axes on a kernel
//! CAN interface both run them so.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::thread::JoinHandle;

use drivebus::canopen::CanBus;
use drivebus::BusError;

use super::{Node, NodeConfig};
use crate::Simulator;

/// Nodes served from their own thread; stopped and joined when dropped (or by [`stop`], which
/// also says why the serving ended early, if it did).
///
/// [`stop`]: ServedNodes::stop
#[derive(Debug)]
pub struct ServedNodes {
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<Result<(), BusError>>>,
}

impl ServedNodes {
    /// Serves the simulated `nodes` on `bus` from a new thread, as drives share a real bus:
    /// each answers for its own node id and sees the others' frames. A master takes its own
    /// endpoint or socket of the bus.
    pub fn serve_on<B: CanBus + Send + 'static>(
        mut bus: B,
        nodes: Vec<(Simulator, NodeConfig)>,
    ) -> Self {
        let stop = Arc::new(AtomicBool::new(false));
        let flag = Arc::clone(&stop);
        let thread = std::thread::spawn(move || {
            let mut nodes: Vec<Node> = nodes
                .into_iter()
                .map(|(sim, config)| Node::new(sim.clone(), config, sim.variant()))
                .collect();
            super::nodes::run_while(&mut nodes, &mut bus, || !flag.load(Ordering::Relaxed))
        });
        Self {
            stop,
            thread: Some(thread),
        }
    }

    /// Stops serving and waits for the thread: `Err` with the bus error that ended the serving
    /// before (a socket that failed). A panic of the serving thread goes on in the caller.
    pub fn stop(mut self) -> Result<(), BusError> {
        self.end().unwrap_or(Ok(()))
    }

    /// Tells the thread to stop and joins it (once): what it ended with.
    fn end(&mut self) -> Option<Result<(), BusError>> {
        self.stop.store(true, Ordering::Relaxed);
        let thread = self.thread.take()?;
        Some(
            thread
                .join()
                .unwrap_or_else(|panic| std::panic::resume_unwind(panic)),
        )
    }
}

impl Drop for ServedNodes {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(thread) = self.thread.take() {
            // Dropped, nobody asks why the serving ended; a panic was already printed.
            let _ = thread.join();
        }
    }
}

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use drivebus::canopen::{CanFrame, NodeId};

    use super::*;

    /// A bus that refuses every frame, as a socket whose interface went away.
    struct Broken;

    impl CanBus for Broken {
        fn send(&mut self, _: &CanFrame) -> Result<(), BusError> {
            Err(BusError::Closed)
        }
        fn recv(&mut self, _: Duration) -> Result<Option<CanFrame>, BusError> {
            Ok(None)
        }
    }

    #[test]
    fn stopping_says_the_bus_error_that_ended_the_serving() {
        let kinco = concat!(env!("CARGO_MANIFEST_DIR"), "/../descriptions/kinco-fd");
        let config = NodeConfig {
            node: NodeId(1),
            heartbeat: None,
        };
        let nodes = vec![(Simulator::load(kinco).unwrap(), config)];
        // The node's boot-up is the first frame: refused before the stop flag is looked at.
        let served = ServedNodes::serve_on(Broken, nodes);
        assert_eq!(served.stop(), Err(BusError::Closed));
    }
}
