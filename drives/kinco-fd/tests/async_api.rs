//! The generated Kinco FD API awaited over the Kinco RS-232 protocol: the same accessors on a
//! handle over the async host (`KincoFd::rs232_async` on `AsyncRs232Client`), whose serial line
//! is an in-memory stream to the simulated drive (drivesim's RS-232 server in a task). A second
//! server on the same simulator, reached through the blocking API, checks that both APIs see the
//! same drive.

use std::time::Duration;

use drivebus::asynch::{Async, TokioTimer};
use drivebus::canopen::can::tokio_adapters::TokioIo;
use drivebus::rs232::async_client::AsyncRs232Client;
use drivebus::rs232::{LoopMode, Rs232Link, StationId};
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
