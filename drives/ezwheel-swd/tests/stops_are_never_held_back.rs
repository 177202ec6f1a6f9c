//! The CiA 402 controlword's stopping commands (profile `stops`; manual section 10.1, lines
//! 2336-2345: shutdown, disable voltage, quick stop, disable operation; bit 8 halt) go out to a
//! node whose vendor-ID the description does not cover; enable operation does not.

use drivebus::canopen::{CanOpenLink, NodeId};
use drivebus::testing::{MemoryBus, Request};
use drivebus::{Error, WriteRefusal};
use ezwheel_swd::Swd;

#[test]
fn stopping_controlwords_go_out_to_a_foreign_node_enable_operation_does_not() {
    let mut memory = MemoryBus::new();
    memory.set_object(0x1018, 1, &0x1234u32.to_le_bytes());
    memory.set_object(0x6040, 0, &0u16.to_le_bytes());
    let mut drive: Swd<CanOpenLink<MemoryBus>> = Swd::canopen(memory, NodeId(0x10));
    assert!(drive.verify_identity().is_err());
    let refused = drive.controlword().write_raw(0x000F).unwrap_err();
    assert!(
        matches!(
            refused,
            Error::WritesRefused {
                reason: WriteRefusal::IdentityMismatch { found: 0x1234, .. },
                ..
            }
        ),
        "{refused:?}"
    );
    let stops = [0x0006, 0x0000, 0x0002, 0x0007, 0x010F];
    for stop in stops {
        assert_eq!(drive.controlword().write_raw(stop), Ok(()), "{stop:#06x}");
    }
    let log = drive.device().link_mut().bus_mut().log();
    let sent: Vec<u16> = log
        .iter()
        .filter_map(|r| match r {
            Request::Download(0x6040, 0, bytes) => Some(u16::from_le_bytes([bytes[0], bytes[1]])),
            _ => None,
        })
        .collect();
    assert_eq!(sent, stops);
}
