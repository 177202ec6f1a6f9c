//! The simulated drive: its parameter store and behaviours, protocol independent.

use std::time::Duration;

use drivegen::ir::Device;

use crate::behaviour::{self, Behaviour, Shared};
use crate::refusal::Refusal;
use crate::store::{ParamId, Store};

/// A drive built from a description.
#[derive(Debug)]
pub struct Drive {
    store: Store,
    behaviours: Vec<Box<dyn Behaviour>>,
    shared: Shared,
}

impl Drive {
    /// A drive at power-on: described defaults, behaviours chosen from the description.
    pub fn new(device: Device) -> Self {
        let mut store = Store::new(device);
        let behaviours = behaviour::for_device(&mut store);
        Self {
            store,
            behaviours,
            shared: Shared::default(),
        }
    }

    /// Makes this the drive at CANopen node `node`: node-relative defaults (`$NODEID+0x180`)
    /// take their value on that node.
    pub fn at_node(&mut self, node: u8) {
        self.store.at_node(node);
    }

    /// The parameter values.
    pub fn store(&self) -> &Store {
        &self.store
    }

    /// Sets a value before clients connect, as the drive's own configuration or measurement
    /// (no checks); it is also stored in non-volatile memory, and the drive restarts with it.
    pub fn preset(&mut self, id: ParamId, value: i128) {
        self.store.set_int(id, value);
        self.store.store();
        let (store, shared) = (&mut self.store, &mut self.shared);
        for b in &mut self.behaviours {
            b.reset(store, shared);
        }
        self.settle();
    }

    /// Lets every behaviour show what the others did.
    fn settle(&mut self) {
        let (store, shared) = (&mut self.store, &mut self.shared);
        for b in &mut self.behaviours {
            b.settle(store, shared);
        }
    }

    /// Writes a value as a client request does: checked against range and allowed values and
    /// the drive's state, then the behaviours react (a reset command reboots the drive).
    pub fn write(&mut self, id: ParamId, bytes: &[u8]) -> Result<(), Refusal> {
        self.store.check(id, bytes)?;
        for b in &self.behaviours {
            b.accept(&self.store, id, bytes)?;
        }
        self.store.set_bytes(id, bytes);
        let (store, shared) = (&mut self.store, &mut self.shared);
        for b in &mut self.behaviours {
            b.written(store, shared, id);
        }
        self.settle();
        if std::mem::take(&mut self.shared.reset_requested) {
            self.reboot();
        }
        Ok(())
    }

    /// Advances time by `dt`: ramps run, faults are taken.
    pub fn tick(&mut self, dt: Duration) {
        let (store, shared) = (&mut self.store, &mut self.shared);
        for b in &mut self.behaviours {
            b.tick(store, shared, dt);
        }
        // A stop no state machine took stays what the watchdog made of the motion.
        self.shared.halt = None;
        self.settle();
    }

    /// The drive received a request: behaviours that watch communication (a serial watchdog)
    /// start counting again.
    pub fn heard(&mut self) {
        for b in &mut self.behaviours {
            b.heard();
        }
    }

    /// Raises a fault with `code`; the state machines react at the next tick.
    pub fn inject_fault(&mut self, code: u16) {
        self.shared.fault = Some(code);
        self.tick(Duration::ZERO);
    }

    /// Blocks the load (`true`): the actual position stops following the demand, so a move
    /// ends in a following error; `false` frees it.
    pub fn block_load(&mut self, blocked: bool) {
        self.shared.load_blocked = blocked;
    }

    /// Puts the simulated home switch at `position` (position units as the drive counts them
    /// now), or removes it (`None`: homing on a switch fails).
    pub fn place_home_switch(&mut self, position: Option<i64>) {
        self.shared.home_switch = crate::behaviour::HomeSwitch(position.map(|p| p as f64));
    }

    /// The active fault code, if any.
    pub fn fault(&self) -> Option<u16> {
        self.shared.fault
    }

    /// Reboots: values reload from non-volatile memory, state machines restart.
    pub fn reboot(&mut self) {
        self.store.reload();
        let (store, shared) = (&mut self.store, &mut self.shared);
        for b in &mut self.behaviours {
            b.reset(store, shared);
        }
        self.settle();
    }
}
