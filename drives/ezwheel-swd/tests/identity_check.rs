//! The identity check on connect over CANopen: `[identity]` covers vendor-ID 0x00000515 (1018h
//! sub 1, manual section 9.5, line 1129). A node reporting another vendor is named with expected
//! and found values, and nothing is written to it until the code explicitly trusts it.

use drivebus::canopen::{CanOpenLink, NodeId};
use drivebus::testing::{MemoryBus, Request};
use drivebus::{Error, WriteRefusal};
use ezwheel_swd::Swd;

/// A node whose 1018h sub 1 holds `vendor_id`, with a controlword to write to.
fn node_of_vendor(vendor_id: u32) -> Swd<CanOpenLink<MemoryBus>> {
    let mut memory = MemoryBus::new();
    memory.set_object(0x1018, 1, &vendor_id.to_le_bytes());
    memory.set_object(0x6040, 0, &0u16.to_le_bytes());
    Swd::canopen(memory, NodeId(0x10))
}

fn downloads(drive: &mut Swd<CanOpenLink<MemoryBus>>) -> usize {
    let log = drive.device().link_mut().bus_mut().log();
    log.iter()
        .filter(|r| matches!(r, Request::Download(..)))
        .count()
}

#[test]
fn the_ez_wheel_vendor_id_verifies_and_writes() {
    let mut drive = node_of_vendor(0x515);
    assert_eq!(drive.verify_identity(), Ok(()));
    assert_eq!(drive.controlword().write_raw(0x06), Ok(()));
    assert_eq!(downloads(&mut drive), 1);
}

#[test]
fn a_foreign_vendor_is_named_and_gets_no_write_until_trusted() {
    let mut drive = node_of_vendor(0x1234);
    let mismatch = WriteRefusal::IdentityMismatch {
        parameter: "vendor_id",
        expected: &[0x515],
        found: 0x1234,
    };
    assert_eq!(
        drive.verify_identity(),
        Err(Error::WritesRefused {
            parameter: "vendor_id",
            reason: mismatch
        })
    );
    // Enable operation (a stopping word would go out: stops_are_never_held_back.rs).
    assert_eq!(
        drive.controlword().write_raw(0x0F),
        Err(Error::WritesRefused {
            parameter: "controlword",
            reason: mismatch
        })
    );
    assert_eq!(downloads(&mut drive), 0, "nothing was sent");
    assert_eq!(drive.controlword().read_raw(), Ok(0), "reads go on");
    drive.trust_unverified();
    assert_eq!(drive.controlword().write_raw(0x0F), Ok(()));
    assert_eq!(downloads(&mut drive), 1);
}

#[test]
fn a_node_without_an_identity_object_is_an_error_not_a_pass() {
    let mut memory = MemoryBus::new();
    memory.set_object(0x6040, 0, &0u16.to_le_bytes());
    let mut drive = Swd::canopen(memory, NodeId(0x10));
    assert!(matches!(drive.verify_identity(), Err(Error::Bus { .. })));
}
