//! The simulated nodes the network manager's tests run on one bus.

// Not every test binary that shares this module boots a Kinco.
#[allow(dead_code)]
pub mod kinco_boot;

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::thread::JoinHandle;

use drivebus::canopen::CanBus;
use drivesim::canopen::{nodes, Node};

/// Nodes served on one endpoint in a thread; stopped and joined on drop.
pub struct Serving {
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
}

impl Serving {
    /// `nodes` on `bus`.
    pub fn start<B: CanBus + Send + 'static>(mut nodes: Vec<Node>, mut bus: B) -> Self {
        Self::spawn(move |running| {
            // Over TCP the run ends with an error when the manager hangs up: that ends a test.
            let _ = nodes::run_while(&mut nodes, &mut bus, running);
        })
    }

    /// `serve` in a thread; it runs while the function it is given says so.
    pub fn spawn(serve: impl FnOnce(&dyn Fn() -> bool) + Send + 'static) -> Self {
        let stop = Arc::new(AtomicBool::new(false));
        let flag = Arc::clone(&stop);
        let thread = std::thread::spawn(move || serve(&|| !flag.load(Ordering::Relaxed)));
        Self {
            stop,
            thread: Some(thread),
        }
    }
}

impl Drop for Serving {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}
