//! The generated Lenze smd API awaited over Modbus RTU over TCP: the same accessors on a handle
//! over the async RTU client (`LenzeSmd::modbus_async` on `AsyncRtuClient`), against the
//! simulated drive (drivesim's RTU loop on a TCP connection). A blocking handle on a second
//! connection to the same simulated drive checks that both APIs see the same drive.

#[path = "support/simulated_smd.rs"]
mod simulated_smd;

use std::time::Duration;

use drivebus::modbus::async_client::{AsyncClientConfig, AsyncRtuClient};
use drivebus::modbus::client::{RtuOverTcpClient, TcpConfig};
use drivebus::modbus::UnitId;
use drivebus::units::{Hertz, Seconds};
use drivebus::{Error, WriteRefusal};
use drivesim::Simulator;
use lenze_smd::types::ControlSource;
use lenze_smd::{params, LenzeSmd, Variant, VariantSelection};

const UNIT: UnitId = UnitId(10);

/// A simulated PC507 smd under Modbus control, served as RTU over TCP on a loopback port.
fn simulated() -> (Simulator, std::net::SocketAddr) {
    let sim = simulated_smd::pc507_under_modbus(&[]);
    let address = drivesim::modbus::rtu_over_tcp::serve(&sim, "127.0.0.1:0", UNIT).unwrap();
    (sim, address)
}

fn config() -> AsyncClientConfig {
    AsyncClientConfig {
        timeout: Duration::from_secs(2),
        ..AsyncClientConfig::default()
    }
}

#[tokio::test]
async fn typed_async_reads_writes_and_read_many_against_the_simulator() {
    let (_sim, address) = simulated();
    let client = RtuOverTcpClient::connect(address, &TcpConfig::default()).unwrap();
    let (mut blocking, selection) = LenzeSmd::open(client, UNIT).unwrap();
    assert_eq!(selection, VariantSelection::Known(Variant::Pc507));
    let client = AsyncRtuClient::connect(address, config()).await.unwrap();
    let mut drive = LenzeSmd::modbus_async(client, UNIT);
    let configuration = drive.parameter_configuration().read_raw().await.unwrap();
    assert_eq!(Variant::selected_by(configuration), Some(Variant::Pc507));
    drive.set_variant(Variant::Pc507);

    // Reads with units, equal to the blocking handle's.
    assert_eq!(
        drive.acceleration_time().read().await,
        blocking.acceleration_time().read()
    );
    assert_eq!(
        drive.maximum_output_frequency().read().await,
        blocking.maximum_output_frequency().read()
    );
    assert_eq!(
        drive.control_source().read().await,
        Ok(ControlSource::C40_MODBUS)
    );

    // Locked: the handle refuses the write before sending, as the drive would (exception 01).
    let refused = drive
        .device()
        .write::<params::AccelerationTime>(Seconds(2.5))
        .await;
    assert!(
        matches!(
            refused,
            Err(Error::WritesRefused {
                parameter: "acceleration_time",
                reason: WriteRefusal::Locked { .. },
            })
        ),
        "{refused:?}"
    );
    assert_eq!(
        refused,
        blocking
            .device()
            .write::<params::AccelerationTime>(Seconds(2.5))
    );

    // Unlocked (#48 = 0 opens the controls): a write, read back through both APIs.
    drive.unlock_commands().write_raw(0).await.unwrap();
    drive
        .device()
        .write::<params::SerialSpeedCommand>(Hertz(20.0))
        .await
        .unwrap();
    assert_eq!(drive.serial_speed_command().read().await, Ok(Hertz(20.0)));
    assert_eq!(blocking.serial_speed_command().read(), Ok(Hertz(20.0)));
    // Beyond the maximum output frequency (C11): refused before sending, naming the bound.
    let beyond = drive
        .device()
        .write::<params::SerialSpeedCommand>(Hertz(75.0))
        .await;
    assert!(matches!(beyond, Err(Error::OutsideBound(_))), "{beyond:?}");
    assert_eq!(drive.serial_speed_command().read().await, Ok(Hertz(20.0)));

    // The smd has no run of sub-indices (Modbus registers only): no indexed accessor.

    // Several parameters at once, equal to the blocking handle's.
    let many = drive
        .read_many_async((
            params::AccelerationTime,
            params::MaximumOutputFrequency,
            params::SerialSpeedCommand,
            params::ControlSource,
        ))
        .await
        .unwrap();
    let once = blocking
        .read_many((
            params::AccelerationTime,
            params::MaximumOutputFrequency,
            params::SerialSpeedCommand,
            params::ControlSource,
        ))
        .unwrap();
    assert_eq!(many, once);
    assert_eq!(many.2, Hertz(20.0));
}
