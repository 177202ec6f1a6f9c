//! The network manager's sans-I/O core (`drivebus::canopen::network::NetworkCore`) fed arbitrary
//! frames from any node, interleaved with time steps, SDO claims and releases, subscriptions
//! and heartbeat monitoring.
//!
//! Input: a list of operations `[op, a, b, ...]`; `op % 6`: 0 a frame `[id lo, id hi, len,
//! 8 data bytes]` (any COB-ID, up to 8 bytes), 1 `a` ms pass and the timers run, 2 claim node
//! `a`'s SDO channel, 3 release it, 4 subscribe node `a` with a queue of `b % 8` events,
//! 5 monitor node `a`'s heartbeat with a timeout of `b` ms. Asserts that
//! * an SDO response handed to a node is on that node's response COB-ID, and only while its
//!   channel is claimed;
//! * a PDO or EMCY event handed to a subscriber is that node's own;
//! * the core sends only what it was told to (SYNC), never an answer to what it received;
//! * the next deadline is never in the past after the timers ran.
#![no_main]

use std::time::Duration;

use drivebus::canopen::network::{NetworkCore, NetworkEvent};
use drivebus::canopen::{CanFrame, NodeId};
use fuzz::Cursor;
use libfuzzer_sys::fuzz_target;

fn node(byte: u8) -> NodeId {
    NodeId((byte % 127) + 1)
}

fuzz_target!(|data: &[u8]| {
    let mut input = Cursor::new(data);
    let mut core = NetworkCore::new();
    let mut now = Duration::ZERO;
    let mut claimed = [false; 128];
    core.set_sync(Some(Duration::from_millis(7)), now);
    while !input.is_empty() {
        match input.u8() % 6 {
            0 => {
                let id = u16::from_le_bytes([input.u8(), input.u8()]) & 0x7FF;
                let len = usize::from(input.u8() % 9);
                let bytes: [u8; 8] = input.array();
                let frame = CanFrame::new(id, &bytes[..len]).expect("a valid frame");
                core.handle(&frame, now);
            }
            1 => {
                now += Duration::from_millis(u64::from(input.u8()));
                core.handle_time(now);
                if let Some(deadline) = core.next_deadline() {
                    assert!(deadline > now, "timers ran, yet {deadline:?} <= {now:?}");
                }
            }
            2 => {
                let n = node(input.u8());
                let free = !claimed[usize::from(n.get())];
                assert_eq!(core.claim_sdo(n), free, "one transfer per node");
                claimed[usize::from(n.get())] = true;
            }
            3 => {
                let n = node(input.u8());
                core.release_sdo(n);
                claimed[usize::from(n.get())] = false;
            }
            4 => {
                let n = node(input.u8());
                core.subscribe(n, usize::from(input.u8() % 8));
            }
            _ => {
                let n = node(input.u8());
                core.monitor(n, Duration::from_millis(u64::from(input.u8())));
            }
        }
        check(&mut core, &claimed);
    }
});

/// Takes everything the core has for anyone and checks it belongs there.
fn check(core: &mut NetworkCore, claimed: &[bool; 128]) {
    while let Some(frame) = core.poll_transmit() {
        assert_eq!(frame.id(), 0x080, "only SYNC was asked for: {frame:?}");
    }
    for id in 1..=127u8 {
        let n = NodeId(id);
        while let Some(frame) = core.next_sdo_response(n) {
            assert!(claimed[usize::from(id)], "node {id} has no transfer");
            assert_eq!(frame.id(), 0x580 + u16::from(id));
        }
        while let Some(event) = core.next_event(n) {
            match event {
                NetworkEvent::Pdo { frame, number } => {
                    assert_eq!(frame.id() & 0x7F, u16::from(id));
                    assert!((1..=4).contains(&number));
                }
                NetworkEvent::Emcy(emcy) => assert_eq!(emcy.node, n),
                _ => {}
            }
        }
    }
}
