//! The two safety settings no signature covers, 6643h "STO active SBC" (RW, line 3265) and 6607h
//! "Safety application configuration valid" (RW, line 3488), are writable through the
//! deliberate `Swd::write_safety_setting`: in Pre-Operational the simulated SWD takes them and
//! they read back; outside Pre-Operational, for another object, for a value outside 6643h's
//! four allowed codes, or while the handle refuses writes, nothing is sent. The
//! safety-function write still refuses them: no signature table lists them.

mod support;

use drivebus::canopen::nmt::NmtState;
use drivebus::canopen::srdo::{SafetyValue, SafetyWriteError};
use drivebus::canopen::NodeId;
use drivebus::testing::SdoRecorder;
use drivebus::{Error, ValueError, WriteRefusal};
use ezwheel_swd::params::{
    SafetyConfigurationValid, StoActivateSbc, StoRestartAcknowledgeBehaviour,
};
use ezwheel_swd::safety_functions::{SBC, STO};
use ezwheel_swd::types::{SafetyCommand, SafetyConfigurationValidity};
use ezwheel_swd::{SafetySettingError, Swd};

#[test]
fn braking_on_sto_and_the_validity_flag_are_written_in_pre_operational() {
    let (mut drive, _node) = support::simulated_swd::start();
    // Factory default: SBC 3, internal braking (lines 3265, 3298).
    assert_eq!(
        drive.sto_activate_sbc().read().unwrap(),
        SafetyCommand::SBC_3
    );
    // A product with an external brake may only use none, SBC 1 or SBC 2 (lines 4059-4062).
    let sbc2 = SafetyValue::of::<StoActivateSbc, _>(drive.device(), SafetyCommand::SBC_2).unwrap();
    assert_eq!(sbc2.object(), (0x6643, 0));
    assert_eq!(sbc2.data(), 0x6660_0200u32.to_le_bytes());
    drive
        .write_safety_setting(NmtState::PreOperational, &[sbc2])
        .unwrap();
    assert_eq!(
        drive.sto_activate_sbc().read().unwrap(),
        SafetyCommand::SBC_2
    );

    let valid = SafetyValue::of::<SafetyConfigurationValid, _>(
        drive.device(),
        SafetyConfigurationValidity::VALID,
    )
    .unwrap();
    assert_eq!(valid.data(), [0xA5], "A5h, line 3484");
    drive
        .write_safety_setting(NmtState::PreOperational, &[valid])
        .unwrap();
    assert_eq!(
        drive.safety_configuration_valid().read().unwrap(),
        SafetyConfigurationValidity::VALID
    );
}

#[test]
fn a_code_6643h_does_not_allow_is_refused_before_anything_is_built() {
    let mut drive = Swd::canopen(SdoRecorder::default(), NodeId(0x10));
    // STO itself is a command code (line 2937) but not a braking mode of 6643h (line 3265).
    let err = SafetyValue::of::<StoActivateSbc, _>(drive.device(), SafetyCommand::STO).unwrap_err();
    assert!(
        matches!(err, Error::Value(ValueError::NotAllowed { .. })),
        "{err:?}"
    );
    assert!(drive.device().link_mut().bus_mut().frames.is_empty());
}

#[test]
fn outside_pre_operational_nothing_is_sent() {
    let mut drive = Swd::canopen(SdoRecorder::default(), NodeId(0x10));
    let none = SafetyValue::of::<StoActivateSbc, _>(drive.device(), SafetyCommand::NONE).unwrap();
    for state in [NmtState::Operational, NmtState::Stopped] {
        assert_eq!(
            drive.write_safety_setting(state, &[none]),
            Err(SafetySettingError::Write(
                SafetyWriteError::NotPreOperational { state }
            ))
        );
    }
    assert!(drive.device().link_mut().bus_mut().frames.is_empty());
}

#[test]
fn a_signed_parameter_is_not_a_setting_and_the_settings_are_in_no_signature() {
    let mut drive = Swd::canopen(SdoRecorder::default(), NodeId(0x10));
    // 6641h is in the STO signature (line 3639): it goes through write_safety_function.
    let behaviour =
        SafetyValue::of::<StoRestartAcknowledgeBehaviour, _>(drive.device(), true).unwrap();
    let sbc1 = SafetyValue::of::<StoActivateSbc, _>(drive.device(), SafetyCommand::SBC_1).unwrap();
    assert_eq!(
        drive.write_safety_setting(NmtState::PreOperational, &[sbc1, behaviour]),
        Err(SafetySettingError::NotAnUnsignedSetting {
            index: 0x6641,
            subindex: 0
        })
    );
    // Neither STO nor SBC signs 6643h, so the signed path refuses it.
    for function in [&STO, &SBC] {
        let instance = if function.instances == 0 { 0 } else { 1 };
        assert!(matches!(
            drive.write_safety_function(NmtState::PreOperational, function, instance, &[sbc1]),
            Err(SafetyWriteError::NotSigned {
                index: 0x6643,
                subindex: 0,
                ..
            })
        ));
    }
    assert!(drive.device().link_mut().bus_mut().frames.is_empty());
}

#[test]
fn a_handle_that_refuses_writes_refuses_the_setting() {
    let mut drive = Swd::canopen(SdoRecorder::default(), NodeId(0x10));
    let sbc1 = SafetyValue::of::<StoActivateSbc, _>(drive.device(), SafetyCommand::SBC_1).unwrap();
    let reason = WriteRefusal::IdentityMismatch {
        parameter: "vendor_id",
        expected: &[0x515],
        found: 0x99,
    };
    drive.device().refuse_writes(reason);
    assert_eq!(
        drive.write_safety_setting(NmtState::PreOperational, &[sbc1]),
        Err(SafetySettingError::Write(SafetyWriteError::WritesRefused(
            reason
        )))
    );
    assert!(drive.device().link_mut().bus_mut().frames.is_empty());
}
