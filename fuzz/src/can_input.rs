//! CAN frames from the fuzzer's bytes: `[shape, 8 data bytes]` per frame.
//!
//! `shape` bit 0 clear: on the COB-ID the target listens to (`ours`), set: on `ours + 1 +
//! (shape >> 4)`, a neighbour's; bit 1 set: a remote frame; bit 2 set: `(shape >> 3) % 9` data
//! bytes instead of the usual 8.

use drivebus::canopen::CanFrame;

use crate::Cursor;

/// Bytes one frame takes in the input.
pub const FRAME_INPUT: usize = 9;

/// The next frame, `None` once the input is used up.
pub fn read(input: &mut Cursor<'_>, ours: u16) -> Option<CanFrame> {
    if input.is_empty() {
        return None;
    }
    let shape = input.u8();
    let data: [u8; 8] = input.array();
    let id = if shape & 1 == 0 {
        ours
    } else {
        (ours + 1 + u16::from(shape >> 4)) & 0x7FF
    };
    let len = if shape & 4 == 0 {
        8
    } else {
        usize::from(shape >> 3) % 9
    };
    let frame = if shape & 2 == 0 {
        CanFrame::new(id, &data[..len])
    } else {
        CanFrame::remote(id, len as u8)
    };
    Some(frame.expect("ids below 0x800 and at most 8 bytes make a frame"))
}
