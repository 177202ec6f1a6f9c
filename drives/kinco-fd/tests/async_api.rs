//! The generated Kinco FD API awaited over the Kinco RS-232 protocol: the same accessors on a
//! handle over the async host (`KincoFd::rs232_async` on `AsyncRs232Client`), whose serial line
//! is an in-memory stream to the simulated drive (drivesim's RS-232 server in a task). A second
//! server on the same simulator, reached through the blocking API, checks that both APIs see the
//! same drive.

use std::time::Duration;

use drivebus::asynch::{Async, TokioTimer};
use drivebus::canopen::can::tokio_adapters::TokioIo;
use drivebus::control::State;
use drivebus::rs232::async_client::AsyncRs232Client;
use drivebus::rs232::{LoopMode, Rs232Link, StationId};
use drivebus::testing::{LinkRequest, Recorded};
use drivebus::units::{Hertz, Percent, Rpm};
use drivebus::{Error, ValueError};
use drivesim::rs232::{InProcessLine, Rs232Server};
use drivesim::Simulator;
use kinco_fd::{params, KincoFd};
use tokio::io::{AsyncReadExt, AsyncWriteExt, DuplexStream};

const DESCRIPTION: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../descriptions/kinco-fd");
const STATION: StationId = StationId(1);
/// One telegram: station, 8 data bytes, checksum.
const TELEGRAM_LEN: usize = 10;

type AsyncKinco = KincoFd<Async<Rs232Link<AsyncRs232Client<TokioIo<DuplexStream>, TokioTimer>>>>;

/// The simulated drive's RS-232 server on the far end of an in-memory stream, in a task that
/// ends when the host hangs up; returns the async handle on the near end.
fn async_kinco(sim: &Simulator) -> AsyncKinco {
    let (near, mut far) = tokio::io::duplex(256);
    let mut server = Rs232Server::new(sim, STATION, LoopMode::PointToPoint);
    tokio::spawn(async move {
        let mut telegram = [0u8; TELEGRAM_LEN];
        while far.read_exact(&mut telegram).await.is_ok() {
            let reply = server.handle(&telegram);
            if far.write_all(&reply).await.is_err() {
                return;
            }
        }
    });
    let host = AsyncRs232Client::new(TokioIo::new(near), TokioTimer, LoopMode::PointToPoint)
        .with_timeout(Duration::from_millis(500));
    KincoFd::rs232_async(host, STATION)
}

#[tokio::test]
async fn typed_async_reads_writes_and_read_many_against_the_simulator() {
    let sim = Simulator::load(DESCRIPTION).unwrap();
    // The simulated motor's encoder: the manual's examples assume 10000 increments.
    sim.preset("encoder_resolution", 10_000).unwrap();
    let mut drive = async_kinco(&sim);
    let line = InProcessLine::new(Rs232Server::new(&sim, STATION, LoopMode::PointToPoint));
    let mut blocking = KincoFd::rs232(line, STATION);

    // A read with units: 60F9h.05, BW = raw × 20 + 100 Hz (default 7: 240 Hz).
    assert_eq!(drive.speed_feedback_filter().read().await, Ok(Hertz(240.0)));
    assert_eq!(
        drive.speed_feedback_filter().read().await,
        blocking.speed_feedback_filter().read()
    );

    // Writes, read back through both APIs; the speed goes through the encoder resolution
    // (6410h.03), read from the drive over RS-232.
    drive
        .speed_feedback_filter()
        .write(Hertz(300.0))
        .await
        .unwrap();
    assert_eq!(drive.speed_feedback_filter().read_raw().await, Ok(10));
    assert_eq!(blocking.speed_feedback_filter().read(), Ok(Hertz(300.0)));
    drive.target_velocity().write(Rpm(150.0)).await.unwrap();
    assert_eq!(drive.target_velocity().read().await, Ok(Rpm(150.0)));
    assert_eq!(
        drive.target_velocity().read_raw().await,
        blocking.target_velocity().read_raw()
    );

    // Refused before anything is sent: the feedforward's range is 0-100 %.
    let refused = drive.k_velocity_ff().write_raw(1000).await;
    assert!(
        matches!(refused, Err(Error::Value(ValueError::OutOfRange { .. }))),
        "{refused:?}"
    );
    assert_eq!(refused, blocking.k_velocity_ff().write_raw(1000));
    assert_eq!(drive.k_velocity_ff().read_raw().await, Ok(100));

    // The Kinco FD has no run of sub-indices described as one (no indexed accessor).

    // Several parameters at once, equal to the blocking handle's.
    let many = drive
        .read_many_async((
            params::SpeedFeedbackFilter,
            params::TargetVelocity,
            params::KVelocityFf,
            params::Statusword,
        ))
        .await
        .unwrap();
    let once = blocking
        .read_many((
            params::SpeedFeedbackFilter,
            params::TargetVelocity,
            params::KVelocityFf,
            params::Statusword,
        ))
        .unwrap();
    assert_eq!(many, once);
    assert_eq!(
        (many.0, many.1, many.2),
        (Hertz(300.0), Rpm(150.0), Percent(100.0))
    );
}

#[tokio::test]
async fn the_cia402_walk_awaited_sends_what_the_blocking_walk_sends() {
    const LIMIT: Duration = Duration::from_secs(3);
    // The blocking walk to operation enabled and back, on one simulated drive.
    let sim = Simulator::load(DESCRIPTION).unwrap();
    let line = InProcessLine::new(Rs232Server::new(&sim, STATION, LoopMode::PointToPoint));
    let mut blocking = KincoFd::new(Recorded::new(KincoFd::rs232(line, STATION).into_link()));
    let deadline = || std::time::Instant::now() + LIMIT;
    blocking.enable_operation(deadline()).unwrap();
    assert_eq!(blocking.cia402_state(), Ok(Some(State::OperationEnabled)));
    blocking.disable(deadline()).unwrap();
    assert_eq!(blocking.cia402_state(), Ok(Some(State::SwitchOnDisabled)));

    // The same walk awaited, on a second simulated drive in the same state.
    let sim = Simulator::load(DESCRIPTION).unwrap();
    let link = async_kinco(&sim).into_link().into_inner();
    let mut drive = KincoFd::new(Async(Recorded::new(link)));
    drive
        .enable_operation_async(&TokioTimer, LIMIT)
        .await
        .unwrap();
    assert_eq!(
        drive.cia402_state_async().await,
        Ok(Some(State::OperationEnabled))
    );
    drive.disable_async(&TokioTimer, LIMIT).await.unwrap();
    assert_eq!(
        drive.cia402_state_async().await,
        Ok(Some(State::SwitchOnDisabled))
    );

    // The same requests in the same order (a status polled more often in one run is one poll),
    // the commands among them: shutdown, switch on, enable operation, disable voltage.
    let sent = drive.device().link_mut().0.log_without_repeats();
    assert_eq!(sent, blocking.device().link_mut().log_without_repeats());
    let commands: Vec<&[u8]> = sent
        .iter()
        .filter_map(|request| match request {
            LinkRequest::Write(_, bytes) => Some(bytes.as_slice()),
            LinkRequest::Read(_) => None,
        })
        .collect();
    assert_eq!(commands, [[0x06, 0], [0x07, 0], [0x0F, 0], [0x00, 0]]);
}

#[tokio::test]
async fn homes_and_moves_through_the_generated_async_motion_methods() {
    use drivebus::control::motion_error::MotionError;
    use drivebus::control::position::{Move, SoftLimits};
    use kinco_fd::types::{HomingMethod, StopMode};

    const LIMIT: Duration = Duration::from_secs(5);
    let sim = Simulator::load(DESCRIPTION).unwrap();
    sim.with(|d| d.place_home_switch(Some(-20_000)));
    let mut drive = async_kinco(&sim);

    // Not operation enabled: refused before anything is sent.
    let refused = drive
        .move_to_async(Move::to(1_000), &TokioTimer, LIMIT)
        .await;
    assert!(
        matches!(refused, Err(MotionError::NotOperationEnabled { .. })),
        "{refused:?}"
    );
    assert_eq!(
        drive.target_position().read_raw().await,
        Ok(0),
        "nothing sent"
    );

    drive.profile_speed().write_raw(200_000).await.unwrap();
    drive
        .profile_acceleration()
        .write_raw(1_000_000)
        .await
        .unwrap();
    drive
        .profile_deceleration()
        .write_raw(1_000_000)
        .await
        .unwrap();
    drive
        .homing_speed_switch()
        .write_raw(100_000)
        .await
        .unwrap();
    drive
        .homing_acceleration()
        .write_raw(1_000_000)
        .await
        .unwrap();
    drive.homing_offset().write_raw(500).await.unwrap();
    drive
        .enable_operation_async(&TokioTimer, LIMIT)
        .await
        .unwrap();

    let home = drive
        .home_async(HomingMethod::METHOD17, &TokioTimer, LIMIT)
        .await;
    assert_eq!(home, Ok(-500), "home is minus the home offset");
    let at = drive
        .move_to_async(Move::to(50_000), &TokioTimer, LIMIT)
        .await;
    assert_eq!(at, Ok(50_000));
    let by = drive
        .move_to_async(Move::by(-10_000), &TokioTimer, LIMIT)
        .await;
    assert_eq!(by, Ok(40_000));

    // Outside the software limits the handle reads (607Dh): refused before anything is sent.
    drive
        .soft_negative_limit()
        .write_raw(-100_000)
        .await
        .unwrap();
    drive.soft_positive_limit().write_raw(45_000).await.unwrap();
    let outside = drive
        .move_to_async(Move::by(10_000), &TokioTimer, LIMIT)
        .await;
    let limits = SoftLimits::between(-100_000, 45_000).unwrap();
    assert_eq!(
        outside,
        Err(MotionError::OutsideLimits {
            target: 50_000,
            limits
        })
    );
    // Nothing written: 607Ah still holds the last move's (relative) target.
    assert_eq!(drive.target_position().read_raw().await, Ok(-10_000));
    drive.soft_negative_limit().write_raw(0).await.unwrap();
    drive.soft_positive_limit().write_raw(0).await.unwrap();

    // A move that cannot end within its limit: halted, then a time out.
    let late = drive
        .move_to_async(
            Move::to(10_000_000),
            &TokioTimer,
            Duration::from_millis(200),
        )
        .await;
    assert!(matches!(late, Err(MotionError::Timeout { .. })), "{late:?}");
    let controlword = drive.controlword().read_raw().await.unwrap();
    assert_ne!(controlword & 0x0100, 0, "halted: {controlword:#06x}");

    // Velocity and torque awaited; the mode display follows.
    let speed = drive
        .run_at_velocity_async(100_000, &TokioTimer, LIMIT)
        .await;
    assert_eq!(speed, Ok(100_000), "target reached at the set velocity");
    assert_eq!(drive.modes_of_operation_display().read_raw().await, Ok(3));
    drive
        .apply_torque_async(10, &TokioTimer, LIMIT)
        .await
        .unwrap();
    assert_eq!(drive.modes_of_operation_display().read_raw().await, Ok(4));

    // Quick stop by the drive's own option code: "stay in quick stop active".
    drive
        .quick_stop_mode()
        .write(StopMode::QUICK_STOP_DECELERATION_STAY)
        .await
        .unwrap();
    drive
        .quick_stop_by_option_code_async(&TokioTimer, LIMIT)
        .await
        .unwrap();
    assert_eq!(
        drive.cia402_state_async().await,
        Ok(Some(State::QuickStopActive))
    );
}
