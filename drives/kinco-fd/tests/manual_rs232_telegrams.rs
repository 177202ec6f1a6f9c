//! Every request telegram of section 9.4 (manual lines 2330-2365, the list in the workspace's
//! `tests/fixtures/kinco-rs232/manual-telegrams.txt`) comes out of the shipped `kinco-fd` crate:
//! each line's action is called on the drive handle over RS-232 (the in-memory bus, which logs
//! each request), and the request is framed with drivebus' telegram codec (station 1) and
//! compared byte for byte with the manual's. The same list is already checked against the codec
//! and a test fixture; this is the description the users get.

use drivebus::rs232::data::Request;
use drivebus::rs232::{telegram, Rs232Link, StationId};
use drivebus::testing::{MemoryBus, Request as Logged};
use drivebus::units::Rpm;
use drivebus::Error;
use kinco_fd::types::{HomingMethod, ModesOfOperation};
use kinco_fd::KincoFd;
use peer_support::kinco_telegrams::printed;

type Drive = KincoFd<Rs232Link<MemoryBus>>;

/// What the manual does at `line`, through the typed API.
fn act(drive: &mut Drive, line: u32) -> Result<(), Error> {
    match line {
        2330 | 2355 => drive.controlword().write_raw(0x2F),
        2339 | 2348 | 2365 => drive.controlword().write_raw(0x0F),
        2344 => drive.controlword().write_raw(0x1F),
        2356 => drive.controlword().write_raw(0x3F),
        2357 => drive.controlword().write_raw(0x4F),
        2358 => drive.controlword().write_raw(0x5F),
        2331 | 2340 => drive.modes_of_operation().write(ModesOfOperation::HOMING),
        2349 => drive.modes_of_operation().write(ModesOfOperation::POSITION),
        2363 => drive.modes_of_operation().write(ModesOfOperation::VELOCITY),
        2332 | 2350 => drive
            .target_position()
            .write(drivebus::units::Increments(50_000.0)),
        2333 | 2345 | 2359 => drive.statusword().read().map(drop),
        2341 => drive.homing_method().write(HomingMethod::METHOD33),
        // "200 rpm" is 0x00085555 DEC, the rounded 546133.33 (ERRATA.md #1, #8): written raw.
        2342 => drive.homing_speed_switch().write_raw(0x08_5555),
        2343 => drive.homing_speed_zero().write(Rpm(150.0)),
        2351 => drive.profile_speed().write_raw(0x08_5555),
        2364 => drive.target_velocity().write(Rpm(150.0)),
        other => panic!("no action for line {other}"),
    }
}

fn framed(logged: &Logged) -> Vec<u8> {
    let request = match logged {
        Logged::Upload(index, subindex) => Request::upload(*index, *subindex),
        Logged::Download(index, subindex, bytes) => {
            Request::download(*index, *subindex, bytes).unwrap()
        }
        other => panic!("not an RS-232 request: {other:?}"),
    };
    telegram::encode(StationId(1), &request.encode()).to_vec()
}

#[test]
fn the_shipped_crate_sends_every_telegram_of_the_manual() {
    let mut memory = MemoryBus::new();
    memory
        .set_object(0x6410, 3, &10_000u32.to_le_bytes())
        .set_object(0x6040, 0, &[0, 0])
        .set_object(0x6041, 0, &[0x37, 0x04])
        .set_object(0x6060, 0, &[0])
        .set_object(0x6098, 0, &[0])
        .set_object(0x6099, 1, &[0; 4])
        .set_object(0x6099, 2, &[0; 4])
        .set_object(0x607A, 0, &[0; 4])
        .set_object(0x6081, 0, &[0; 4])
        .set_object(0x60FF, 0, &[0; 4]);
    let mut drive = KincoFd::rs232(memory, StationId(1));
    let vectors = printed();
    assert_eq!(vectors.len(), 23);
    for (line, manual) in vectors {
        act(&mut drive, line).unwrap_or_else(|e| panic!("line {line}: {e}"));
        let log = drive.device().link_mut().bus_mut().log();
        assert_eq!(framed(log.last().unwrap()), manual, "line {line}");
    }
}
