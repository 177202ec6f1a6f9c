//! The methods the blocking and the async network handles share word for word: each shell's
//! `shared.update` runs a closure on its state (`core`, `ended`), the async one then wakes its
//! router so what was queued goes out at once.

/// NMT, raw frames, SYNC, heartbeat monitoring and status, over `self.shared.update`.
macro_rules! manager_methods {
    () => {
        /// Sends the NMT `command` to `node`, or to every node with `None`.
        pub fn nmt(
            &self,
            command: $crate::canopen::nmt::NmtCommand,
            node: Option<NodeId>,
        ) -> Result<(), BusError> {
            self.send(command.frame(node))
        }

        /// Queues any frame (an RPDO, a TIME stamp) for sending.
        pub fn send(&self, frame: $crate::canopen::frame::CanFrame) -> Result<(), BusError> {
            self.shared.update(|state| match &state.ended {
                Some(error) => Err(error.clone()),
                None if state.core.transmit(frame) => Ok(()),
                None => Err(BusError::CanQueueFull),
            })
        }

        /// Produces a SYNC every `period`, the first one now; `None` stops it.
        pub fn set_sync(&self, period: Option<Duration>) {
            let now = self.shared.now();
            self.shared.update(|state| state.core.set_sync(period, now));
        }

        /// Expects a heartbeat from `node` at least every `timeout` (set its producer time,
        /// 1017h, shorter); a longer silence is reported as
        /// [`NetworkEvent::Lost`](crate::canopen::network::NetworkEvent::Lost), the next
        /// heartbeat as [`NetworkEvent::Back`](crate::canopen::network::NetworkEvent::Back).
        pub fn monitor_heartbeat(&self, node: NodeId, timeout: Duration) {
            self.shared
                .update(|state| state.core.monitor(node, timeout));
        }

        /// Stops monitoring `node`'s heartbeat.
        pub fn forget_heartbeat(&self, node: NodeId) {
            self.shared.update(|state| state.core.forget(node));
        }

        /// What the manager knows about `node`: NMT state, heartbeat lost, last EMCY.
        pub fn status(&self, node: NodeId) -> $crate::canopen::network::NodeStatus {
            self.shared.update(|state| state.core.status(node))
        }

        /// SDO responses dropped because no transfer to their node was in flight (late
        /// answers after a timeout, duplicates, another master's traffic).
        pub fn stale_sdo_responses(&self) -> u64 {
            self.shared.update(|state| state.core.stale_sdo_responses())
        }
    };
}
pub(crate) use manager_methods;
