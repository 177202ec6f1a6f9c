//! The SDO client fed arbitrary server frames: expedited, segmented and block transfers, both
//! directions.
//!
//! Input: `[mode, length, block size, frames...]`; `mode % 4` picks upload, download, block
//! upload or block download; `length` is the upload buffer's or the download's size; each frame
//! is `[step, shape, 8 data bytes]` (see src/can_input.rs), `step` milliseconds after the one
//! before. Asserts that
//! * the client only ever sends full 8-byte data frames on its request COB-ID;
//! * frames on other COB-IDs are ignored: no progress, nothing sent;
//! * an upload completes with at most its buffer's length, a download with exactly its data's;
//! * a finished transfer has no deadline, stays finished and sends nothing more after its
//!   final (abort) frame;
//! * a transfer that has not finished times out once its deadline passes.
#![no_main]

use std::time::Duration;

use drivebus::canopen::sdo::{Progress, SdoClient, Transfer};
use drivebus::canopen::NodeId;
use fuzz::{can_input, Cursor};
use libfuzzer_sys::fuzz_target;

const NODE: u8 = 5;
const TIMEOUT: Duration = Duration::from_millis(100);
const INDEX: u16 = 0x2000;

fuzz_target!(|data: &[u8]| {
    let mut input = Cursor::new(data);
    let mode = input.u8() % 4;
    let length = usize::from(input.u8());
    let block_size = input.u8();
    let client = SdoClient::new(NodeId::new(NODE).expect("a node id"), TIMEOUT);
    let mut buf = vec![0u8; length];
    let payload: Vec<u8> = (0..length).map(|i| i as u8).collect();
    let now = Duration::ZERO;
    match mode {
        0 => run(
            client.upload(INDEX, 1, &mut buf, now),
            &mut input,
            Expect::AtMost(length),
        ),
        1 => run(
            client.download(INDEX, 1, &payload, now),
            &mut input,
            Expect::Exactly(length),
        ),
        2 => run(
            client.block_upload(INDEX, 1, &mut buf, block_size, now),
            &mut input,
            Expect::AtMost(length),
        ),
        _ => run(
            client.block_download(INDEX, 1, &payload, now),
            &mut input,
            Expect::Exactly(length),
        ),
    }
});

/// The length a completed transfer may report.
#[derive(Clone, Copy)]
enum Expect {
    AtMost(usize),
    Exactly(usize),
}

fn run(mut transfer: impl Transfer, input: &mut Cursor<'_>, expect: Expect) {
    let request_cob = 0x600 + u16::from(NODE);
    let response_cob = transfer.response_cob();
    let mut now = Duration::ZERO;
    let mut finished = false;
    drain(&mut transfer, request_cob);
    loop {
        now += Duration::from_millis(u64::from(input.u8()));
        let Some(frame) = can_input::read(input, response_cob) else {
            break;
        };
        let timed_out = transfer.deadline().is_some_and(|deadline| deadline <= now);
        let foreign = !timed_out && frame.id() != response_cob;
        let progress = if timed_out {
            transfer.handle_timeout(now)
        } else {
            transfer.handle(&frame, now)
        };
        if foreign {
            assert_eq!(progress, Progress::Pending, "a foreign frame made progress");
        }
        match progress {
            Progress::Pending => {}
            _ if finished => panic!("a finished transfer reported {progress:?} again"),
            Progress::Done(len) => {
                match expect {
                    Expect::AtMost(max) => assert!(len <= max, "uploaded {len} into {max} bytes"),
                    Expect::Exactly(sent) => assert_eq!(len, sent, "download length"),
                }
                finished = true;
            }
            Progress::Failed(_) => finished = true,
        }
        let sent = drain(&mut transfer, request_cob);
        if finished {
            assert_eq!(
                transfer.deadline(),
                None,
                "a finished transfer keeps a deadline"
            );
            assert!(sent <= 1, "a finished transfer sent {sent} frames");
        } else if foreign {
            assert_eq!(sent, 0, "a foreign frame made the client send");
        }
    }
    if let Some(deadline) = transfer.deadline() {
        let progress = transfer.handle_timeout(deadline);
        assert!(
            matches!(progress, Progress::Failed(_)),
            "no timeout at the deadline: {progress:?}"
        );
    }
}

/// Takes every queued frame, checking its shape; returns how many there were.
fn drain(transfer: &mut impl Transfer, request_cob: u16) -> usize {
    let mut count = 0;
    while let Some(frame) = transfer.poll_transmit() {
        assert_eq!(frame.id(), request_cob, "sent on another COB-ID");
        assert!(!frame.is_remote() && frame.dlc() == 8, "sent {frame:?}");
        count += 1;
        assert!(count <= 128, "a burst of more than a block");
    }
    count
}
