//! The async SLCAN and candump buses fed an arbitrary byte stream, read in chunks of a chosen
//! size (what an adapter or a relay sends, split as the transport splits it).
//!
//! Input: one byte, the chunk size (1 to 64, from the byte's low six bits plus one), then the
//! stream. The same stream goes to both buses. Never panics and never waits: every receive
//! ends in a frame, a report or the end of the stream, and each consumes input, so both buses
//! reach the end (`UnexpectedEof`) within as many receives as there are bytes.
#![no_main]

use drivebus::canopen::can::async_candump::AsyncCandumpBus;
use drivebus::canopen::can::async_slcan::AsyncSlcanBus;
use drivebus::canopen::can::AsyncCanBus;
use drivebus::BusError;
use fuzz::chunks::{now, Chunks};
use libfuzzer_sys::fuzz_target;

/// Receives until the end of the stream, which must come within `bound` receives.
fn drain(bound: usize, mut receive: impl FnMut() -> Result<(), BusError>) {
    for _ in 0..=bound {
        match receive() {
            Ok(()) => {}
            Err(BusError::Io(std::io::ErrorKind::UnexpectedEof)) => return,
            Err(other) => panic!("only the end of the stream ends it: {other:?}"),
        }
    }
    panic!("more than {bound} receives without reaching the end");
}

fuzz_target!(|input: &[u8]| {
    let Some((&size, stream)) = input.split_first() else {
        return;
    };
    let chunk = usize::from(size & 0x3F) + 1;
    let mut slcan = AsyncSlcanBus::new(Chunks {
        data: stream,
        chunk,
    });
    drain(stream.len(), || now(slcan.recv_event()).map(drop));
    let mut candump = AsyncCandumpBus::new(
        Chunks {
            data: stream,
            chunk,
        },
        Chunks { data: &[], chunk },
    );
    drain(stream.len(), || now(candump.recv()).map(drop));
});
