//! The store-and-reset helper against a scripted drive: the order of the commands, the wait for
//! the drive to come back, and what each failure reports.

#[path = "support/fake_clock.rs"]
mod fake_clock;
#[path = "support/simulated_drive.rs"]
mod simulated_drive;

use core::time::Duration;

use drivebus::modbus::{ModbusLink, Table, UnitId};
use drivebus::{BusError, Error};
use fake_clock::FakeClock;
use lafert_smartris::types::OperationMode;
use lafert_smartris::{params, RebootWait, Smartris, StoreResetError};
use simulated_drive::{SimulatedDrive, OPERATION_MODE, RESET, STORE};

const WAIT: RebootWait = RebootWait {
    deadline: Duration::from_secs(2),
    poll_interval: Duration::from_millis(250),
};

fn drive(sim: SimulatedDrive) -> Smartris<ModbusLink<SimulatedDrive>> {
    Smartris::modbus(sim, UnitId(1))
}

#[test]
fn writes_stores_resets_and_waits_until_the_drive_answers() {
    let mut sim = SimulatedDrive::in_standby(1);
    sim.silent_requests_after_reset = 3;
    let mut drive = drive(sim);
    let mut clock = FakeClock::default();
    let waited = drive
        .write_store_reset::<params::OperationMode>(OperationMode::VELOCITY, WAIT, &mut clock)
        .unwrap();
    // Three silent polls, the fourth answers.
    assert_eq!(clock.sleeps, 4);
    assert_eq!(waited, Duration::from_millis(1000));
    let sim = drive.into_link().into_bus();
    assert_eq!(sim.writes(), [(OPERATION_MODE, 2), (STORE, 1), (RESET, 1)]);
    assert_eq!(sim.memory.register(Table::Holding, OPERATION_MODE), Some(2));
}

#[test]
fn a_drive_that_stays_silent_ends_in_no_answer_after_the_deadline() {
    let mut sim = SimulatedDrive::in_standby(2);
    sim.silent_requests_after_reset = u32::MAX;
    let mut drive = drive(sim);
    let mut clock = FakeClock::default();
    let error = drive.store_and_reset(WAIT, &mut clock).unwrap_err();
    match error {
        StoreResetError::NoAnswerAfterReset { waited, last } => {
            assert_eq!(waited, WAIT.deadline);
            assert_eq!(last.bus(), Some(&BusError::Timeout));
        }
        other => panic!("expected NoAnswerAfterReset, got {other:?}"),
    }
    assert_eq!(clock.sleeps, 8, "2 s in steps of 250 ms");
}

#[test]
fn a_refused_value_is_not_stored() {
    let mut drive = drive(SimulatedDrive::in_standby(2));
    // Operation mode 0 is readable but not writable (allowed = [1, 2]): refused before sending.
    let error = drive
        .write_store_reset::<params::OperationMode>(
            OperationMode::NONE,
            WAIT,
            &mut FakeClock::default(),
        )
        .unwrap_err();
    assert!(
        matches!(error, StoreResetError::Write(Error::Value(_))),
        "{error:?}"
    );
    assert!(drive.into_link().into_bus().writes().is_empty());
}

#[test]
fn a_failed_store_does_not_reset() {
    let mut sim = SimulatedDrive::in_standby(2);
    sim.memory = drivebus::testing::MemoryBus::new(); // no register 0x0000: exception 0x02
    let mut drive = drive(sim);
    let error = drive
        .store_and_reset(WAIT, &mut FakeClock::default())
        .unwrap_err();
    let StoreResetError::Store(cause) = &error else {
        panic!("expected Store, got {error:?}");
    };
    assert_eq!(
        cause.bus(),
        Some(&BusError::ModbusException {
            function: 0x06,
            code: drivebus::modbus::ExceptionCode::IllegalDataAddress
        })
    );
    assert!(error.to_string().contains("store command (0x0000)"));
    assert_eq!(
        drive.into_link().into_bus().memory.log().len(),
        1,
        "only the store was sent"
    );
}

#[test]
fn a_reset_the_drive_does_not_answer_is_not_an_error_if_it_comes_back() {
    let mut sim = SimulatedDrive::in_standby(2);
    sim.reset_unanswered = true;
    sim.silent_requests_after_reset = 1;
    let mut drive = drive(sim);
    let waited = drive
        .store_and_reset(WAIT, &mut FakeClock::default())
        .unwrap();
    assert_eq!(waited, Duration::from_millis(500));
}
