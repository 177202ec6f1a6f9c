//! The procedures a handle runs on connect, awaited, against the simulated drives over the async
//! Modbus TCP client, with the blocking procedures' conclusions: `verify_identity_async` on
//! Lafert (the covered firmware 242 and a foreign one) and `detect_variant_async` on the smd (a
//! covered configuration, #50 = 400, and one no variant covers, 401).

use std::time::Duration;

use drivebus::modbus::async_client::{AsyncClientConfig, AsyncTcpClient};
use drivebus::modbus::{AsyncRegisterBus, UnitId};
use drivebus::units::Rpm;
use drivebus::{Error, WriteRefusal};
use drivesim::modbus::tcp::TcpServer;
use lafert_smartris::Smartris;
use lenze_smd::{LenzeSmd, Variant, VariantSelection};

/// The drive of description `name` with `preset` raw value preset, served over Modbus TCP at
/// unit 1 while the server lives, and an async client connected to it.
async fn served(name: &str, preset: &[(&str, i128)]) -> (TcpServer, impl AsyncRegisterBus) {
    let descriptions = concat!(env!("CARGO_MANIFEST_DIR"), "/../descriptions/");
    let sim = drivesim::Simulator::load(format!("{descriptions}{name}")).unwrap();
    for (parameter, raw) in preset {
        sim.preset(parameter, *raw).unwrap();
    }
    let server = sim.serve_modbus_tcp("127.0.0.1:0", UnitId(1)).unwrap();
    let config = AsyncClientConfig {
        timeout: Duration::from_secs(2),
        ..AsyncClientConfig::default()
    };
    let client = AsyncTcpClient::connect(server.local_addr(), config)
        .await
        .unwrap();
    (server, client)
}

/// The simulated Lafert drive holding firmware `release`, and an async client to it.
async fn lafert_with_firmware(release: i128) -> (TcpServer, impl AsyncRegisterBus) {
    served(
        "lafert-smartris",
        &[("fw_release", release), ("full_scale_velocity", 3000)],
    )
    .await
}

#[tokio::test]
async fn the_covered_firmware_verifies_and_writes() {
    let (_server, client) = lafert_with_firmware(242).await;
    let mut drive = Smartris::modbus_async(client, UnitId(1));
    assert_eq!(drive.verify_identity_async().await, Ok(()));
    assert_eq!(drive.speed_setpoint().write(Rpm(1500.0)).await, Ok(()));
}

#[tokio::test]
async fn a_foreign_firmware_is_named_and_refuses_writes_until_trusted() {
    let (_server, client) = lafert_with_firmware(226).await;
    let mut drive = Smartris::modbus_async(client, UnitId(1));
    let mismatch = WriteRefusal::IdentityMismatch {
        parameter: "fw_release",
        expected: &[242],
        found: 226,
    };
    assert_eq!(
        drive.verify_identity_async().await,
        Err(Error::WritesRefused {
            parameter: "fw_release",
            reason: mismatch
        })
    );
    assert_eq!(
        drive.speed_setpoint().write(Rpm(1500.0)).await,
        Err(Error::WritesRefused {
            parameter: "speed_setpoint",
            reason: mismatch
        })
    );
    assert_eq!(
        drive.speed_setpoint().read().await,
        Ok(Rpm(0.0)),
        "reads go on"
    );
    drive.trust_unverified();
    assert_eq!(drive.speed_setpoint().write(Rpm(1500.0)).await, Ok(()));
}

#[tokio::test]
async fn a_covered_configuration_is_selected() {
    let (_server, client) = served("lenze-smd", &[("parameter_configuration", 400)]).await;
    let mut drive = LenzeSmd::modbus_async(client, UnitId(1));
    assert_eq!(
        drive.detect_variant_async().await,
        Ok(VariantSelection::Known(Variant::Pc400))
    );
    assert_eq!(drive.device().write_refusal(), None);
}

#[tokio::test]
async fn an_unknown_configuration_refuses_writes_and_moved_reads() {
    let (_server, client) = served("lenze-smd", &[("parameter_configuration", 401)]).await;
    let mut drive = LenzeSmd::modbus_async(client, UnitId(1));
    assert_eq!(
        drive.detect_variant_async().await,
        Ok(VariantSelection::Unknown(401))
    );
    assert_eq!(
        drive.device().write_refusal(),
        Some(WriteRefusal::UnknownVariant {
            selector: "parameter_configuration",
            value: 401
        })
    );
    // c25 moves between PC400 and PC507: nothing is guessed.
    assert!(matches!(
        drive.serial_baud_rate().read().await,
        Err(Error::VariantUnknown { .. })
    ));
    drive.set_variant(Variant::Pc507);
    assert_eq!(drive.device().write_refusal(), None);
}
