//! The async unlock sessions against the simulated smd (RTU over TCP): `unlock_<name>_async`
//! returns an `AsyncUnlocked` guard whose `lock().await` locks; a guard dropped without it
//! leaves the lock owed, and the handle's next request sends the lock command first. The
//! drive's own answer is checked with raw register writes, which no handle account filters:
//! exception 01 once locked. The generated machine `operation` walks to running and back under
//! an unlock, sending what the blocking walk sends.

#[path = "support/simulated_smd.rs"]
mod simulated_smd;

use std::time::Duration;

use drivebus::asynch::{Async, TokioTimer};
use drivebus::modbus::async_client::tokio::TokioTcp;
use drivebus::modbus::async_client::{AsyncClientConfig, AsyncRtuClient};
use drivebus::modbus::client::{RtuOverTcpClient, TcpConfig};
use drivebus::modbus::{AsyncRegisterBus, ExceptionCode, ModbusLink, StaticLimits, UnitId};
use drivebus::testing::{LinkRequest, Recorded};
use drivebus::units::Hertz;
use drivebus::{BusError, Error, WriteRefusal};
use lenze_smd::operation::State;
use lenze_smd::unlock::Controls;
use lenze_smd::{params, AsyncUnlocked, Command, LenzeSmd, UnlockError, Variant};

const UNIT: UnitId = UnitId(10);
/// The serial speed command #40 (holding 0x0028), in 0.1 Hz.
const SERIAL_SPEED: u16 = 0x0028;

type AsyncSmd = LenzeSmd<Async<ModbusLink<AsyncRtuClient<TokioTcp, TokioTimer>, StaticLimits>>>;

/// A simulated PC507 smd under Modbus control with `presets`, served as RTU over TCP.
fn simulated(presets: &[(&str, i128)]) -> std::net::SocketAddr {
    let sim = simulated_smd::pc507_under_modbus(presets);
    drivesim::modbus::rtu_over_tcp::serve(&sim, "127.0.0.1:0", UNIT).unwrap()
}

async fn connect(address: std::net::SocketAddr) -> AsyncSmd {
    let config = AsyncClientConfig {
        timeout: Duration::from_secs(2),
        ..AsyncClientConfig::default()
    };
    let client = AsyncRtuClient::connect(address, config).await.unwrap();
    let mut drive = LenzeSmd::modbus_async(client, UNIT);
    drive.set_variant(Variant::Pc507);
    drive
}

/// A raw write of #40 over the drive's client, past the handle's account: the drive judges.
async fn raw_speed_write(drive: &mut AsyncSmd, raw: u16) -> Result<(), BusError> {
    let bus = drive.device().link_mut().0.bus_mut();
    bus.write_register(UNIT, SERIAL_SPEED, raw).await
}

/// The drive's answer to a write while locked: exception 01.
fn refused_as_locked(outcome: Result<(), BusError>) -> bool {
    matches!(outcome, Err(BusError::ModbusException { code, .. }) if code == ExceptionCode::IllegalFunction)
}

/// The controls unlocked, and the serial speed set to 30 Hz under the unlock.
async fn unlocked_at_30_hz(
    drive: &mut AsyncSmd,
) -> AsyncUnlocked<'_, ModbusLink<AsyncRtuClient<TokioTcp, TokioTimer>, StaticLimits>, Controls> {
    let mut session = drive.unlock_controls_async().await.unwrap();
    let speed = session.serial_speed_command().write(Hertz(30.0)).await;
    assert_eq!(speed, Ok(()));
    session
}

#[tokio::test]
async fn lock_awaited_locks_the_drive() {
    let mut drive = connect(simulated(&[])).await;
    let session = unlocked_at_30_hz(&mut drive).await;
    session.lock().await.unwrap();
    assert!(!drive.device().lock_owed());
    assert_eq!(drive.serial_speed_command().read().await, Ok(Hertz(30.0)));
    assert!(refused_as_locked(raw_speed_write(&mut drive, 200).await));
    // The handle refuses before sending, as the blocking one does after `lock()`.
    let refused = drive
        .device()
        .write::<params::SerialSpeedCommand>(Hertz(20.0))
        .await;
    assert!(
        matches!(
            refused,
            Err(Error::WritesRefused {
                reason: WriteRefusal::Locked { .. },
                ..
            })
        ),
        "{refused:?}"
    );
}

#[tokio::test]
async fn a_dropped_guard_s_lock_goes_out_before_the_next_request() {
    let mut drive = connect(simulated(&[])).await;
    let session = unlocked_at_30_hz(&mut drive).await;
    drop(session); // without `lock()`: nothing can be awaited in `Drop`
    assert!(drive.device().lock_owed());
    // Nothing has been sent yet: the drive is still unlocked and takes a raw write.
    assert_eq!(raw_speed_write(&mut drive, 250).await, Ok(()));
    // The next request through the handle sends the lock first, then reads.
    assert_eq!(drive.serial_speed_command().read().await, Ok(Hertz(25.0)));
    assert!(!drive.device().lock_owed());
    assert!(refused_as_locked(raw_speed_write(&mut drive, 200).await));
    // A new session unlocks again, and its lock is owed too when dropped.
    let session = drive.unlock_controls_async().await.unwrap();
    drop(session);
    assert!(drive.device().lock_owed());
    assert_eq!(
        drive.unlock_parameter_writing_async(0).await.err(),
        None,
        "the owed lock, then the grant: whatever the password, the drive judges it"
    );
}

#[tokio::test]
async fn a_requirement_not_met_writes_nothing_as_in_the_blocking_api() {
    let mut drive = connect(simulated(&[("control_source", 8)])).await;
    let refused = drive.unlock_controls_async().await.err();
    assert_eq!(
        refused,
        Some(UnlockError::Requirement {
            parameter: "control_source",
            found: 8,
            allowed: &[10, 11]
        })
    );
}

#[tokio::test]
async fn the_operation_machine_awaited_sends_what_the_blocking_walk_sends() {
    const LIMIT: Duration = Duration::from_secs(5);
    let presets = [("acceleration_time", 0), ("serial_speed_command", 300)];
    // The blocking walk, under an unlock of the controls, on one simulated drive.
    let client = RtuOverTcpClient::connect(simulated(&presets), &TcpConfig::default()).unwrap();
    let mut blocking = LenzeSmd::new(Recorded::new(LenzeSmd::modbus(client, UNIT).into_link()));
    blocking.set_variant(Variant::Pc507);
    let deadline = || std::time::Instant::now() + LIMIT;
    let mut session = blocking.unlock_controls().unwrap();
    let drive = session.drive();
    drive.goto_operation(State::Running, deadline()).unwrap();
    assert_eq!(drive.operation_state(), Ok(Some(State::Running)));
    drive.goto_operation(State::Stopped, deadline()).unwrap();
    assert_eq!(drive.operation_state(), Ok(Some(State::Stopped)));
    session.lock().unwrap();

    // The same walk awaited, on a second simulated drive in the same state.
    let link = connect(simulated(&presets)).await.into_link().0;
    let mut awaited = LenzeSmd::new(Async(Recorded::new(link)));
    awaited.set_variant(Variant::Pc507);
    let mut session = awaited.unlock_controls_async().await.unwrap();
    let drive = session.drive();
    let timer = TokioTimer;
    drive
        .goto_operation_async(State::Running, &timer, LIMIT)
        .await
        .unwrap();
    assert_eq!(
        drive.operation_state_async().await,
        Ok(Some(State::Running))
    );
    drive
        .goto_operation_async(State::Stopped, &timer, LIMIT)
        .await
        .unwrap();
    assert_eq!(
        drive.operation_state_async().await,
        Ok(Some(State::Stopped))
    );
    session.lock().await.unwrap();

    let sent = awaited.device().link_mut().0.log_without_repeats();
    assert_eq!(sent, blocking.device().link_mut().log_without_repeats());
    // Unlock (#48 = 0), start, stop, lock (#1).
    let writes = sent
        .iter()
        .filter(|request| matches!(request, LinkRequest::Write(..)))
        .count();
    assert_eq!(writes, 4, "{sent:?}");
}

#[tokio::test]
async fn commands_under_an_async_unlock_start_and_stop_the_drive() {
    let mut drive = connect(simulated(&[("acceleration_time", 0)])).await;
    let mut session = unlocked_at_30_hz(&mut drive).await;
    session
        .command(Command::SerialSpeedReference)
        .await
        .unwrap();
    session.command(Command::Start).await.unwrap();
    assert_eq!(
        session.drive().operation_state_async().await,
        Ok(Some(State::Running))
    );
    session.command(Command::Stop).await.unwrap();
    assert_eq!(
        session.drive().operation_state_async().await,
        Ok(Some(State::Stopped))
    );
    session.lock().await.unwrap();
}
