//! The async RS-232 host against the simulator's RS-232 server: through a socat pty pair (the
//! tokio serial stream), and through an in-memory pipe where the test decides when the drive
//! answers (a dropped exchange, a late answer, a closed line).

use std::time::Duration;

use drivebus::asynch::{AsyncLink, TokioTimer};
use drivebus::canopen::can::tokio_adapters::TokioIo;
use drivebus::canopen::ObjectAddress;
use drivebus::rs232::async_client::AsyncRs232Client;
use drivebus::rs232::telegram::TELEGRAM_LEN;
use drivebus::rs232::{LoopMode, Rs232Link, StationId};
use drivebus::stream::TokioSerialStream;
use drivebus::BusError;
use drivesim::Simulator;
use peer_support::pty_pair;
use tokio::io::{duplex, AsyncReadExt, AsyncWriteExt, DuplexStream};

const TIMEOUT: Duration = Duration::from_millis(300);

fn fixture() -> Simulator {
    let sim =
        Simulator::load(concat!(env!("CARGO_MANIFEST_DIR"), "/fixtures/kinco-rs232")).unwrap();
    sim.preset("encoder_resolution", 10_000).unwrap();
    sim
}

fn raw(sim: &Simulator, name: &str) -> i128 {
    sim.with(|drive| drive.store().int(drive.store().id(name).unwrap()).unwrap())
}

fn object(index: u16, bytes: u16) -> ObjectAddress {
    ObjectAddress {
        index,
        subindex: 0,
        bytes,
    }
}

const OPERATION_MODE: u16 = 0x6060;
const TARGET_SPEED: u16 = 0x60FF;
const CONTROLWORD: u16 = 0x6040;
const STATUSWORD: u16 = 0x6041;

/// The manual's speed-mode sequence (section 9.4) through an async link.
async fn run_speed_mode<L: AsyncLink<Protocol = drivebus::rs232::Rs232>>(
    link: &mut L,
    sim: &Simulator,
) {
    link.write(&object(OPERATION_MODE, 1), &[3]).await.unwrap();
    link.write(&object(TARGET_SPEED, 4), &409_600i32.to_le_bytes())
        .await
        .unwrap();
    link.write(&object(CONTROLWORD, 2), &0x000Fu16.to_le_bytes())
        .await
        .unwrap();
    assert_eq!(raw(sim, "operation_mode"), 3);
    assert_eq!(raw(sim, "target_speed"), 409_600);
    let mut out = [0u8; 4];
    assert_eq!(link.read(&object(TARGET_SPEED, 4), &mut out).await, Ok(4));
    assert_eq!(i32::from_le_bytes(out), 409_600);
    let len = link.read(&object(STATUSWORD, 2), &mut out).await.unwrap();
    assert_eq!(len, 2);
    assert_eq!(
        i128::from(u16::from_le_bytes([out[0], out[1]])),
        raw(sim, "statusword")
    );
}

async fn over_a_pty(mode: LoopMode) {
    let sim = fixture();
    let pty = pty_pair();
    let config = drivebus::rs232::client::Rs232Config {
        timeout: TIMEOUT,
        mode,
        ..Default::default()
    };
    let mut line =
        drivebus::rs232::client::open_line(pty.server.to_str().unwrap(), &config).unwrap();
    let mut server = sim.rs232_server(StationId(1), mode);
    std::thread::spawn(move || drivesim::rs232::serve(&mut server, &mut line));
    let port = TokioSerialStream::open_8n1(pty.client.to_str().unwrap(), 38_400).unwrap();
    let client = AsyncRs232Client::new(port, TokioTimer, mode).with_timeout(TIMEOUT);
    run_speed_mode(&mut Rs232Link::new(client, StationId(1)), &sim).await;
}

#[tokio::test]
async fn the_speed_mode_sequence_runs_over_a_pty_point_to_point() {
    over_a_pty(LoopMode::PointToPoint).await;
}

#[tokio::test]
async fn the_speed_mode_sequence_runs_over_a_pty_in_a_multi_point_loop() {
    over_a_pty(LoopMode::MultiPoint).await;
}

type Link = Rs232Link<AsyncRs232Client<TokioIo<DuplexStream>, TokioTimer>>;

/// An async link on one end of an in-memory line; the other end is the drive's.
fn in_memory() -> (Link, DuplexStream) {
    let (ours, theirs) = duplex(256);
    let client = AsyncRs232Client::new(TokioIo::new(ours), TokioTimer, LoopMode::PointToPoint)
        .with_timeout(TIMEOUT);
    (Rs232Link::new(client, StationId(1)), theirs)
}

/// Reads one request telegram from the line.
async fn request(line: &mut DuplexStream) -> [u8; TELEGRAM_LEN] {
    let mut telegram = [0u8; TELEGRAM_LEN];
    line.read_exact(&mut telegram).await.unwrap();
    telegram
}

#[tokio::test]
async fn a_dropped_exchange_is_closed_and_its_late_answer_not_taken_for_the_next() {
    let sim = fixture();
    let mut server = sim.rs232_server(StationId(1), LoopMode::PointToPoint);
    let (mut link, mut line) = in_memory();
    let mut out = [0u8; 4];
    // The read of the statusword goes out; the drive has not answered when it is dropped.
    let dropped = tokio::time::timeout(
        Duration::from_millis(20),
        link.read(&object(STATUSWORD, 2), &mut out),
    )
    .await;
    assert!(dropped.is_err());
    let stale = request(&mut line).await;
    // Its answer comes late, while the next read waits for the line to fall quiet; then the
    // next request (the operation mode) is answered.
    let drive = tokio::spawn(async move {
        tokio::time::sleep(Duration::from_millis(5)).await;
        line.write_all(&server.handle(&stale)).await.unwrap();
        let next = request(&mut line).await;
        line.write_all(&server.handle(&next)).await.unwrap();
        line
    });
    assert_eq!(link.read(&object(OPERATION_MODE, 1), &mut out).await, Ok(1));
    assert_eq!(i128::from(out[0] as i8), raw(&sim, "operation_mode"));
    drop(drive.await.unwrap());
}

#[tokio::test]
async fn a_line_closed_under_a_pending_exchange_is_a_typed_error() {
    let (mut link, mut line) = in_memory();
    let closer = tokio::spawn(async move {
        let _ = request(&mut line).await;
        drop(line);
    });
    let mut out = [0u8; 4];
    let outcome = tokio::time::timeout(
        Duration::from_secs(5),
        link.read(&object(STATUSWORD, 2), &mut out),
    )
    .await;
    closer.await.unwrap();
    assert_eq!(
        outcome,
        Ok(Err(BusError::Io(std::io::ErrorKind::UnexpectedEof)))
    );
}
