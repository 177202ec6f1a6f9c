//! The deliberate write of safety-function parameters against the simulated SWD: SLSa 3's
//! positive limit and monitoring time are written in Pre-Operational and 3058h sub 3 then holds
//! the signature the SLSa table (lines 3745-3783) gives over the drive's values; outside
//! Pre-Operational, or with a value the signature does not cover, nothing is sent.
//!
//! The simulated SWD has only the objects the manual describes; the units 6600h/6602h and the
//! Safe_out mapping 26F8h, which the SLSa signature covers, are only named by the manual
//! (COVERAGE.md), so the test's bus answers them with zeros in the drive's place.

mod support;

use drivebus::canopen::nmt::NmtState;
use drivebus::canopen::srdo::{
    write_safety_function, write_safety_function_async, SafetyValue, SafetyWriteError,
};
use drivebus::canopen::{NodeId, SdoBus};
use drivebus::indexed::At;
use drivebus::testing::{now, Immediate, SdoRecorder};
use drivebus::units::{Milliseconds, Rpm};
use drivebus::{BusError, WriteRefusal};
use ezwheel_swd::params::{SlsaPositiveVelocityLimitRun, SlsaTimeToPositiveVelocityMonitoringRun};
use ezwheel_swd::safety_functions::{SLS, SLSA};
use ezwheel_swd::Swd;

/// SLSa 3's members of the two runs (3052h and 3051h sub 3).
type SlsaPositiveVelocityLimit3 = At<SlsaPositiveVelocityLimitRun, 3>;
type SlsaTimeToPositiveVelocityMonitoring3 = At<SlsaTimeToPositiveVelocityMonitoringRun, 3>;

/// The objects the SLSa signature covers that the manual only names: read as zeros.
fn only_named(index: u16) -> bool {
    matches!(index, 0x6600..=0x6603 | 0x26F8)
}

/// The simulated drive's SDO bus, with the only-named objects answered as zeros.
struct WithNamedAsZero<'a, B>(&'a mut B);

impl<B: SdoBus> SdoBus for WithNamedAsZero<'_, B> {
    fn upload(
        &mut self,
        node: NodeId,
        index: u16,
        subindex: u8,
        out: &mut [u8],
    ) -> Result<usize, BusError> {
        if only_named(index) {
            out[..4].fill(0);
            return Ok(4);
        }
        self.0.upload(node, index, subindex, out)
    }
    fn download(
        &mut self,
        node: NodeId,
        index: u16,
        subindex: u8,
        data: &[u8],
    ) -> Result<(), BusError> {
        self.0.download(node, index, subindex, data)
    }
}

/// CRC-16-CCITT, x^16 + x^12 + x^5 + 1, start value 0, bit by bit (manual lines 3497-3562).
fn crc16_ccitt(bytes: &[u8]) -> u16 {
    bytes.iter().fold(0u16, |mut crc, byte| {
        crc ^= u16::from(*byte) << 8;
        for _ in 0..8 {
            crc = if crc & 0x8000 != 0 {
                (crc << 1) ^ 0x1021
            } else {
                crc << 1
            };
        }
        crc
    })
}

/// The bytes the SLSa table signs for SLSa 3, in its order, from `bus` (little-endian, at the
/// table's widths).
fn slsa3_signed_bytes<B: SdoBus>(bus: &mut B, node: NodeId) -> Vec<u8> {
    let mut bytes = Vec::new();
    let mut sign = |index: u16, subindex: u8, width: usize| {
        let mut out = [0u8; 8];
        let len = bus.upload(node, index, subindex, &mut out).unwrap();
        assert!(len >= width, "{index:04X}:{subindex} has {len} bytes");
        bytes.extend_from_slice(&out[..width]);
    };
    sign(0x6600, 0, 4);
    sign(0x6602, 0, 4);
    for (index, width) in [
        (0x3051, 2),
        (0x3052, 4),
        (0x3053, 2),
        (0x3054, 2),
        (0x3055, 4),
        (0x3056, 2),
        (0x3057, 4),
    ] {
        sign(index, 3, width);
    }
    for index in 0x66F0..=0x66FF {
        for subindex in 1..=8 {
            sign(index, subindex, 4);
        }
    }
    for subindex in 1..=6 {
        sign(0x26F1, subindex, 4);
    }
    for index in [0x26F8, 0x2624, 0x2625] {
        for subindex in 1..=8 {
            sign(index, subindex, 4);
        }
    }
    bytes
}

#[test]
fn slsa3_is_written_and_signed_in_pre_operational() {
    let (mut drive, _running) = support::simulated_swd::start();
    let node = NodeId(support::simulated_swd::NODE);
    let values = [
        SafetyValue::of::<SlsaPositiveVelocityLimit3, _>(drive.device(), Rpm(500.0)).unwrap(),
        SafetyValue::of::<SlsaTimeToPositiveVelocityMonitoring3, _>(
            drive.device(),
            Milliseconds(120.0),
        )
        .unwrap(),
    ];
    let bus = drive.device().link_mut().bus_mut();
    let written = write_safety_function(
        &mut WithNamedAsZero(bus),
        node,
        NmtState::PreOperational,
        &SLSA,
        3,
        &values,
    )
    .unwrap();

    assert_eq!(
        drive.slsa_positive_velocity_limit(3).read().unwrap(),
        Rpm(500.0)
    );
    assert_eq!(drive.slsa_signature(3).read_raw().unwrap(), written);
    let bus = drive.device().link_mut().bus_mut();
    let expected = crc16_ccitt(&slsa3_signed_bytes(&mut WithNamedAsZero(bus), node));
    assert_eq!(written, expected);
    // The other instances keep their signatures.
    assert_eq!(drive.slsa_signature(2).read_raw().unwrap(), 0);
}

#[test]
fn outside_pre_operational_nothing_is_sent() {
    let mut drive = Swd::canopen(SdoRecorder::default(), NodeId(0x10));
    let value = SafetyValue::of::<SlsaPositiveVelocityLimit3, _>(drive.device(), Rpm(500.0))
        .expect("no run-time input is read for an in-range value");
    let frames_before = drive.device().link_mut().bus_mut().frames.len();
    for state in [NmtState::Operational, NmtState::Stopped] {
        assert_eq!(
            drive.write_safety_function(state, &SLSA, 3, &[value]),
            Err(SafetyWriteError::NotPreOperational { state })
        );
    }
    assert_eq!(
        drive.device().link_mut().bus_mut().frames.len(),
        frames_before
    );
}

#[test]
fn a_value_the_signature_does_not_cover_is_refused_before_sending() {
    let mut drive = Swd::canopen(SdoRecorder::default(), NodeId(0x10));
    let value =
        SafetyValue::of::<SlsaPositiveVelocityLimit3, _>(drive.device(), Rpm(500.0)).unwrap();
    let frames_before = drive.device().link_mut().bus_mut().frames.len();
    // SLSa 3's limit is not in SLSa 2's signature, nor in any SLS signature.
    assert_eq!(
        drive.write_safety_function(NmtState::PreOperational, &SLSA, 2, &[value]),
        Err(SafetyWriteError::NotSigned {
            function: "SLSa",
            index: 0x3052,
            subindex: 3
        })
    );
    assert!(matches!(
        drive.write_safety_function(NmtState::PreOperational, &SLS, 3, &[value]),
        Err(SafetyWriteError::NotSigned { .. })
    ));
    assert_eq!(
        drive.write_safety_function(NmtState::PreOperational, &SLSA, 9, &[value]),
        Err(SafetyWriteError::NoSuchFunction {
            function: "SLSa",
            instance: 9
        })
    );
    assert_eq!(
        drive.device().link_mut().bus_mut().frames.len(),
        frames_before
    );
}

#[test]
fn a_handle_that_refuses_writes_refuses_the_safety_write() {
    let mut drive = Swd::canopen(SdoRecorder::default(), NodeId(0x10));
    let value =
        SafetyValue::of::<SlsaPositiveVelocityLimit3, _>(drive.device(), Rpm(500.0)).unwrap();
    let reason = WriteRefusal::IdentityMismatch {
        parameter: "vendor_id",
        expected: &[0x515],
        found: 0x99,
    };
    drive.device().refuse_writes(reason);
    let frames_before = drive.device().link_mut().bus_mut().frames.len();
    assert_eq!(
        drive.write_safety_function(NmtState::PreOperational, &SLSA, 3, &[value]),
        Err(SafetyWriteError::WritesRefused(reason))
    );
    assert_eq!(
        drive.device().link_mut().bus_mut().frames.len(),
        frames_before
    );
}

#[test]
fn slsa3_awaited_is_written_and_signed_as_the_blocking_write_does() {
    let (mut drive, _running) = support::simulated_swd::start();
    let node = NodeId(support::simulated_swd::NODE);
    let values = [
        SafetyValue::of::<SlsaPositiveVelocityLimit3, _>(drive.device(), Rpm(450.0)).unwrap(),
        SafetyValue::of::<SlsaTimeToPositiveVelocityMonitoring3, _>(
            drive.device(),
            Milliseconds(80.0),
        )
        .unwrap(),
    ];
    let bus = drive.device().link_mut().bus_mut();
    // The async write, over the simulated drive's bus answered at once.
    let written = now(write_safety_function_async(
        &mut Immediate(WithNamedAsZero(bus)),
        node,
        NmtState::PreOperational,
        &SLSA,
        3,
        &values,
    ))
    .expect("the immediate bus never waits")
    .unwrap();

    assert_eq!(
        drive.slsa_positive_velocity_limit(3).read().unwrap(),
        Rpm(450.0)
    );
    assert_eq!(drive.slsa_signature(3).read_raw().unwrap(), written);
    let bus = drive.device().link_mut().bus_mut();
    let expected = crc16_ccitt(&slsa3_signed_bytes(&mut WithNamedAsZero(bus), node));
    assert_eq!(written, expected);
    // The blocking write of the same values finds the same signature.
    let bus = drive.device().link_mut().bus_mut();
    let again = write_safety_function(
        &mut WithNamedAsZero(bus),
        node,
        NmtState::PreOperational,
        &SLSA,
        3,
        &values,
    );
    assert_eq!(again, Ok(written));
}

#[tokio::test]
async fn the_async_handle_writes_over_slcan_and_stops_where_the_drive_has_no_object() {
    let (mut blocking, running) = support::simulated_swd::start();
    let mut drive = support::simulated_swd::async_swd(&running.sim).await;
    // The values are scaled over the async link.
    let limit = SafetyValue::of_async::<SlsaPositiveVelocityLimit3, _>(drive.device(), Rpm(500.0))
        .await
        .unwrap();
    assert_eq!(
        Ok(limit),
        SafetyValue::of::<SlsaPositiveVelocityLimit3, _>(blocking.device(), Rpm(500.0))
    );

    // Refused before anything is sent, as on the blocking handle.
    assert_eq!(
        drive
            .write_safety_function_async(NmtState::Operational, &SLSA, 3, &[limit])
            .await,
        Err(SafetyWriteError::NotPreOperational {
            state: NmtState::Operational
        })
    );
    assert_eq!(
        drive
            .write_safety_function_async(NmtState::PreOperational, &SLSA, 2, &[limit])
            .await,
        Err(SafetyWriteError::NotSigned {
            function: "SLSa",
            index: 0x3052,
            subindex: 3
        })
    );
    assert_eq!(
        blocking.slsa_positive_velocity_limit(3).read(),
        Ok(Rpm(0.0))
    );

    // The value is written; the read-back stops at 6600h, which the simulated drive does not
    // have (the manual only names it), so the signature is not written.
    let stopped = drive
        .write_safety_function_async(NmtState::PreOperational, &SLSA, 3, &[limit])
        .await;
    assert!(
        matches!(
            stopped,
            Err(SafetyWriteError::Bus {
                index: 0x6600,
                subindex: 0,
                ..
            })
        ),
        "{stopped:?}"
    );
    assert_eq!(
        blocking.slsa_positive_velocity_limit(3).read(),
        Ok(Rpm(500.0))
    );
    assert_eq!(blocking.slsa_signature(3).read_raw(), Ok(0));
}

#[test]
fn a_handle_that_refuses_writes_refuses_the_async_safety_write() {
    let mut drive = Swd::canopen_async(Immediate(SdoRecorder::default()), NodeId(0x10));
    let value = now(SafetyValue::of_async::<SlsaPositiveVelocityLimit3, _>(
        drive.device(),
        Rpm(500.0),
    ))
    .unwrap()
    .unwrap();
    let reason = WriteRefusal::IdentityMismatch {
        parameter: "vendor_id",
        expected: &[0x515],
        found: 0x99,
    };
    drive.device().refuse_writes(reason);
    let frames_before = drive.device().link_mut().0.bus_mut().0.frames.len();
    assert_eq!(
        now(drive.write_safety_function_async(NmtState::PreOperational, &SLSA, 3, &[value])),
        Some(Err(SafetyWriteError::WritesRefused(reason)))
    );
    assert_eq!(
        drive.device().link_mut().0.bus_mut().0.frames.len(),
        frames_before
    );
}
