//! The CiA 402 driver in-process: our device double behind a statusword source other than an
//! SDO read of 0x6041 (as a TPDO-fed application would supply it).
#![cfg(feature = "canopen")]

use std::time::{Duration, Instant};

use drivebus::canopen::{CanOpenLink, NodeId};
use drivebus::control::device::Cia402Device;
use drivebus::control::driver::{self, ControlError, StuckReason};
use drivebus::control::{State, Target};
use drivebus::testing::MemoryBus;
use drivebus::{Device, VariantId};

#[path = "support/cia402_objects.rs"]
mod objects;

use objects::{HaltQuirk, Mode, Standard};

/// A bus holding only the controlword and the STO word: reading 0x6041 over it would fail.
fn device() -> Device<CanOpenLink<MemoryBus>> {
    let mut bus = MemoryBus::new();
    bus.set_object(0x6040, 0, &[0, 0])
        .set_object(0x2003, 0, &[0, 0]);
    Device::new(CanOpenLink::new(bus, NodeId(5)), VariantId::default())
}

/// The statusword of `drive` after it saw the controlword last written to the bus.
fn follow(drive: &mut Cia402Device, device: &mut Device<CanOpenLink<MemoryBus>>) -> u16 {
    let written = device
        .link_mut()
        .bus_mut()
        .object(0x6040, 0)
        .map(|b| u16::from_le_bytes([b[0], b[1]]));
    if let Some(controlword) = written.filter(|&w| w != drive.controlword()) {
        drive.write_controlword(controlword);
    }
    drive.tick();
    drive.statusword()
}

fn soon() -> Instant {
    Instant::now() + Duration::from_secs(2)
}

#[test]
fn the_statusword_can_come_from_another_source() {
    let mut device = device();
    let mut drive = Cia402Device::in_state(State::NotReadyToSwitchOn);
    driver::drive_to_with::<Standard, _>(&mut device, Target::OperationEnabled, soon(), |d| {
        Ok(follow(&mut drive, d))
    })
    .unwrap();
    assert_eq!(drive.state(), State::OperationEnabled);
    drive.raise_fault();
    driver::drive_to_with::<Standard, _>(&mut device, Target::SwitchedOn, soon(), |d| {
        Ok(follow(&mut drive, d))
    })
    .unwrap();
    assert_eq!(drive.state(), State::SwitchedOn);
}

#[test]
fn without_the_source_the_driver_reads_0x6041_and_reports_its_absence() {
    let mut device = device();
    let error =
        driver::drive_to::<Standard, _>(&mut device, Target::OperationEnabled, soon()).unwrap_err();
    assert!(matches!(error, ControlError::Bus(_)), "{error}");
    let frozen = Instant::now() + Duration::from_millis(20);
    let error =
        driver::drive_to_with::<Standard, _>(&mut device, Target::OperationEnabled, frozen, |_| {
            Ok(0x0240)
        })
        .unwrap_err();
    assert!(
        matches!(error, ControlError::Stuck { reason: StuckReason::NoResponse { transition, .. }, .. } if transition.name == "2"),
        "{error}"
    );
}

/// A bus with halt set in the controlword and the display already showing `shown`.
fn halted_device(shown: i8) -> Device<CanOpenLink<MemoryBus>> {
    let mut device = device();
    let bus = device.link_mut().bus_mut();
    bus.set_object(0x6040, 0, &0x010Fu16.to_le_bytes())
        .set_object(0x6060, 0, &[0])
        .set_object(0x6061, 0, &shown.to_le_bytes());
    device
}

fn controlword(device: &mut Device<CanOpenLink<MemoryBus>>) -> Option<Vec<u8>> {
    device
        .link_mut()
        .bus_mut()
        .object(0x6040, 0)
        .map(<[u8]>::to_vec)
}

#[test]
fn quirk_mode_change_needs_halt_clear_clears_halt_before_the_mode() {
    let mut quirky = halted_device(3);
    driver::set_mode::<HaltQuirk, _>(&mut quirky, Mode(3), soon()).unwrap();
    assert_eq!(controlword(&mut quirky), Some(vec![0x0F, 0x00]));
    let mut standard = halted_device(3);
    driver::set_mode::<Standard, _>(&mut standard, Mode(3), soon()).unwrap();
    assert_eq!(
        controlword(&mut standard),
        Some(vec![0x0F, 0x01]),
        "halt left alone"
    );
}

#[test]
fn an_unconfirmed_mode_names_both_modes() {
    let mut device = halted_device(1);
    let deadline = Instant::now() + Duration::from_millis(20);
    let error = driver::set_mode::<Standard, _>(&mut device, Mode(-3), deadline).unwrap_err();
    assert_eq!(
        error,
        ControlError::ModeNotConfirmed {
            requested: -3,
            displayed: 1
        }
    );
}
