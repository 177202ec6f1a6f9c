//! The CiA 402 driver in-process: our device double behind a statusword source other than an
//! SDO read of 0x6041 (as a TPDO-fed application would supply it).
#![cfg(feature = "canopen")]

use std::time::{Duration, Instant};

use drivebus::canopen::{CanOpenLink, NodeId};
use drivebus::control::device::Cia402Device;
use drivebus::control::driver::{self, ControlError, StuckReason};
use drivebus::control::{State, Target};
use drivebus::memory::MemoryBus;
use drivebus::{Device, VariantId};

#[path = "support/cia402_objects.rs"]
mod objects;

use objects::Standard;

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
