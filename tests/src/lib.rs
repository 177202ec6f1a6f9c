//! Workspace-level tests live in `tests/api/`; this library holds what they share: the drive
//! API generated from the RS-232 test fixture (`fixtures/kinco-rs232/device.toml`).

/// The generated API of `fixtures/kinco-rs232`: a few Kinco FD objects over CANopen, Modbus
/// and the Kinco RS-232 protocol.
pub mod kinco_rs232 {
    include!(concat!(env!("OUT_DIR"), "/kinco_rs232.rs"));
}
