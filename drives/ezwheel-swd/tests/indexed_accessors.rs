//! Members described once over a run of sub-indices are reached through one indexed accessor:
//! `drive.sls_velocity_limit(3)` reads 6693h:03, and a sub-index outside the run is refused
//! before anything is sent. The SWD's writable runs are all safety-function parameters
//! (`safety = true`: no setter), so the values are placed in the object dictionary directly.

mod support;

use drivebus::canopen::NodeId;
use drivebus::interpret::OutsideRange;
use drivebus::testing::MemoryBus;
use drivebus::units::Rpm;
use drivebus::{Error, ValueError};
use ezwheel_swd::indexed::{SafetyControlword2Command, StandardErrorField};
use ezwheel_swd::types::SafetyCommand;
use support::simulated_swd::start;

#[test]
fn an_indexed_accessor_reaches_the_sub_index_it_names() {
    let mut memory = MemoryBus::new();
    for sub in 2..=4 {
        let value: u32 = if sub == 3 { 0x6690_0100 } else { 0 };
        memory.set_object(0x66F1, sub, &value.to_le_bytes());
    }
    let mut drive = ezwheel_swd::Swd::canopen(memory, NodeId(0x10));
    assert_eq!(
        drive.safety_controlword_2_command(3).read().unwrap(),
        SafetyCommand::SLS_1,
        "6690 0100h is SLS [1] (line 2944)"
    );
    // The neighbours are distinct objects.
    assert_eq!(
        drive.safety_controlword_2_command(2).read().unwrap(),
        SafetyCommand::NONE
    );
    assert_eq!(
        drive.safety_controlword_2_command(4).read().unwrap(),
        SafetyCommand::NONE
    );
    assert_eq!(drive.safety_controlword_2_command(3).subindex(), 3);
}

#[test]
fn an_indexed_accessor_converts_units_like_any_accessor() {
    // 6693h is scaled by the vl dimension factor 604Ch (numerator / denominator): raw rpm × 2.
    let mut memory = MemoryBus::new();
    memory.set_object(0x6693, 8, &450u32.to_le_bytes());
    memory.set_object(0x604C, 1, &2i32.to_le_bytes());
    memory.set_object(0x604C, 2, &1i32.to_le_bytes());
    let mut drive = ezwheel_swd::Swd::canopen(memory, NodeId(0x10));
    assert_eq!(drive.sls_velocity_limit(8).read_raw().unwrap(), 450);
    assert_eq!(drive.sls_velocity_limit(8).read().unwrap(), Rpm(900.0));
}

#[test]
fn a_sub_index_outside_the_run_is_a_typed_error_and_nothing_is_sent() {
    let (mut drive, _node) = start();
    for outside in [0, 9, 255] {
        let err = drive
            .safety_controlword_2_command(outside)
            .read()
            .unwrap_err();
        assert_eq!(
            err,
            Error::Value(ValueError::OutOfRange {
                parameter: "safety_controlword_2_command",
                value: OutsideRange::Int {
                    raw: i128::from(outside),
                    min: 1,
                    max: 8
                },
            })
        );
    }
    // The run of 66F0h starts at sub-index 2 (sub-indices 1, 7 and 8 are fixed, read-only).
    assert!(drive.safety_controlword_1_command(1).read().is_err());
    assert_eq!(SafetyControlword2Command::<()>::FIRST, 1);
    assert_eq!(StandardErrorField::<()>::LAST, 254);
}

#[test]
fn the_error_history_is_one_accessor_over_254_sub_indices() {
    let (mut drive, _node) = start();
    assert_eq!(drive.error_history_count().read().unwrap(), 0);
    assert_eq!(drive.standard_error_field(1).read().unwrap(), 0);
    assert_eq!(drive.standard_error_field(254).read().unwrap(), 0);
    assert!(drive.standard_error_field(255).read().is_err());
}

#[test]
fn an_out_of_range_sub_index_sends_no_request() {
    let mut memory = MemoryBus::new();
    memory.set_object(0x66F1, 8, &0x6632_0000u32.to_le_bytes());
    let mut drive = ezwheel_swd::Swd::canopen(memory, NodeId(0x10));
    assert!(drive.safety_controlword_2_command(9).read().is_err());
    assert!(drive.safety_controlword_2_command(0).read().is_err());
    assert!(drive.device().link_mut().bus_mut().log().is_empty());
    // In range, the request reaches the object of that sub-index.
    assert_eq!(
        drive.safety_controlword_2_command(8).read().unwrap(),
        SafetyCommand::ERROR_ACK
    );
    assert_eq!(drive.device().link_mut().bus_mut().log().len(), 1);
}
