//! The generated SWD API awaited: the same accessors on a handle over the async SDO client
//! (`Swd::canopen_async`), on SLCAN over a loopback TCP connection to the simulated drive
//! (drivesim's CANopen node on the blocking SLCAN bus). A second node on the same simulator,
//! reached through the blocking API, checks that both APIs see the same drive.

mod support;

use std::time::Duration;

use drivebus::asynch::{Async, TokioTimer};
use drivebus::control::{ControlError, State};
use drivebus::interpret::OutsideRange;
use drivebus::testing::{LinkRequest, Recorded};
use drivebus::units::Rpm;
use drivebus::{Error, ValueError};
use drivesim::Simulator;
use ezwheel_swd::{params, Swd};
use support::simulated_swd::{async_swd, start};

#[tokio::test]
async fn typed_async_reads_writes_and_read_many_against_the_simulator() {
    let (mut blocking, running) = start();
    let mut drive = async_swd(&running.sim).await;

    // A read with units: 6046h:02 through the vl dimension factor (1/1 at start).
    let max = drive.vl_velocity_max_amount().read().await.unwrap();
    assert_eq!(Ok(max), blocking.vl_velocity_max_amount().read());

    // A write, read back through both APIs.
    drive
        .vl_dimension_factor_numerator()
        .write(1)
        .await
        .unwrap();
    drive
        .vl_dimension_factor_denominator()
        .write(10)
        .await
        .unwrap();
    drive.vl_target_velocity().write(Rpm(29.8)).await.unwrap();
    assert_eq!(drive.vl_target_velocity().read_raw().await, Ok(298));
    assert_eq!(drive.vl_target_velocity().read().await, Ok(Rpm(29.8)));
    assert_eq!(blocking.vl_target_velocity().read(), Ok(Rpm(29.8)));
    // The limit scales as well, the same in both APIs.
    assert_eq!(
        drive.vl_velocity_max_amount().read().await,
        blocking.vl_velocity_max_amount().read()
    );

    // Refused before anything is sent: the factor's range is 1..=i32::MAX.
    let refused = drive.vl_dimension_factor_denominator().write(0).await;
    assert!(
        matches!(refused, Err(Error::Value(ValueError::OutOfRange { .. }))),
        "{refused:?}"
    );
    assert_eq!(refused, blocking.vl_dimension_factor_denominator().write(0));
    assert_eq!(drive.vl_dimension_factor_denominator().read().await, Ok(10));

    // A run of sub-indices (6693h:01..08), one indexed accessor, equal to the blocking one;
    // outside the run the sub-index is refused before anything is sent. (A safety run: no
    // setter, as on the blocking handle.)
    for sub in 1..=8 {
        assert_eq!(
            drive.sls_velocity_limit(sub).read().await,
            blocking.sls_velocity_limit(sub).read(),
            "6693h:{sub:02x}"
        );
    }
    assert_eq!(
        drive.sls_velocity_limit(9).read().await,
        Err(Error::Value(ValueError::OutOfRange {
            parameter: "sls_velocity_limit",
            value: OutsideRange::Int {
                raw: 9,
                min: 1,
                max: 8
            },
        }))
    );

    // Several parameters at once, equal to the blocking handle's.
    let many = drive
        .read_many_async((
            params::VlTargetVelocity,
            params::VlDimensionFactorNumerator,
            params::VlDimensionFactorDenominator,
            params::VlVelocityMaxAmount,
        ))
        .await
        .unwrap();
    let once = blocking
        .read_many((
            params::VlTargetVelocity,
            params::VlDimensionFactorNumerator,
            params::VlDimensionFactorDenominator,
            params::VlVelocityMaxAmount,
        ))
        .unwrap();
    assert_eq!(many, once);
    assert_eq!((many.0, many.1, many.2), (Rpm(29.8), 1, 10));
}

/// Three seconds from now, the blocking driver's deadline.
fn deadline() -> std::time::Instant {
    std::time::Instant::now() + LIMIT
}

/// The async driver's limit.
const LIMIT: Duration = Duration::from_secs(3);

#[tokio::test]
async fn the_cia402_walk_awaited_sends_what_the_blocking_walk_sends() {
    // The blocking walk to operation enabled and back, on one simulated drive.
    let (blocking, _running) = start();
    let mut blocking = Swd::new(Recorded::new(blocking.into_link()));
    assert_eq!(blocking.cia402_state(), Ok(Some(State::SwitchOnDisabled)));
    blocking.enable_operation(deadline()).unwrap();
    assert_eq!(blocking.cia402_state(), Ok(Some(State::OperationEnabled)));
    blocking.disable(deadline()).unwrap();
    assert_eq!(blocking.cia402_state(), Ok(Some(State::SwitchOnDisabled)));

    // The same walk awaited, on a second one in the same state.
    let sim = Simulator::load(support::simulated_swd::DESCRIPTION).unwrap();
    let link = async_swd(&sim).await.into_link().into_inner();
    let mut drive = Swd::new(Async(Recorded::new(link)));
    let timer = TokioTimer;
    assert_eq!(
        drive.cia402_state_async().await,
        Ok(Some(State::SwitchOnDisabled))
    );
    drive.enable_operation_async(&timer, LIMIT).await.unwrap();
    assert_eq!(
        drive.cia402_state_async().await,
        Ok(Some(State::OperationEnabled))
    );
    drive.disable_async(&timer, LIMIT).await.unwrap();
    assert_eq!(
        drive.cia402_state_async().await,
        Ok(Some(State::SwitchOnDisabled))
    );

    // The same requests in the same order (a status polled more often in one run is one poll).
    let sent = drive.device().link_mut().0.log_without_repeats();
    let expected = blocking.device().link_mut().log_without_repeats();
    assert_eq!(sent, expected);
    let commands: Vec<Vec<u8>> = sent
        .iter()
        .filter_map(|request| match request {
            LinkRequest::Write(_, bytes) => Some(bytes.clone()),
            LinkRequest::Read(_) => None,
        })
        .collect();
    // Shutdown, switch on, enable operation; then disable voltage.
    assert_eq!(commands, [[0x06, 0], [0x07, 0], [0x0F, 0], [0x00, 0]]);
}

#[tokio::test]
async fn an_async_walk_out_of_time_says_where_the_drive_is_stuck() {
    let sim = Simulator::load(support::simulated_swd::DESCRIPTION).unwrap();
    let mut drive = async_swd(&sim).await;
    // A limit too short for the drive: the error names the state and the missing transition,
    // as the blocking driver's does at its deadline.
    let outcome = drive
        .enable_operation_async(&TokioTimer, Duration::ZERO)
        .await;
    assert!(
        matches!(
            outcome,
            Err(ControlError::Bus(Error::Bus {
                cause: drivebus::BusError::Timeout,
                ..
            })) | Err(ControlError::Stuck { .. })
        ),
        "{outcome:?}"
    );
    // The drive is usable afterwards: the dropped request left the bus consistent.
    drive
        .enable_operation_async(&TokioTimer, LIMIT)
        .await
        .unwrap();
    drive.quick_stop_async(&TokioTimer, LIMIT).await.unwrap();
    assert_ne!(
        drive.cia402_state_async().await,
        Ok(Some(State::OperationEnabled))
    );
    drive.fault_reset_async(&TokioTimer, LIMIT).await.unwrap();
    drive.disable_async(&TokioTimer, LIMIT).await.unwrap();
}
