//! The generated Lafert API awaited: the same accessors on a handle over the async Modbus TCP
//! client (`Smartris::modbus_async`), against the simulated drive (drivesim's Modbus TCP server)
//! and against an independent implementation, pymodbus serving a Lafert-like register map
//! (tests/peers/modbus_server.py, as `peer_pymodbus.rs` for the blocking client).

use std::time::Duration;

use drivebus::asynch::{Async, TokioTimer};
use drivebus::modbus::async_client::{AsyncClientConfig, AsyncRtuClient, AsyncTcpClient};
use drivebus::modbus::client::{ModbusTcpClient, TcpConfig};
use drivebus::modbus::UnitId;
use drivebus::testing::{LinkRequest, Recorded};
use drivebus::units::{Rpm, Volts};
use drivebus::{Error, OutsideBound};
use lafert_smartris::modbus_run::State;
use lafert_smartris::types::{ControlWord, DriveStatus};
use lafert_smartris::{params, Smartris};

fn config() -> AsyncClientConfig {
    AsyncClientConfig {
        timeout: Duration::from_secs(2),
        max_in_flight: 8,
        ..AsyncClientConfig::default()
    }
}

#[tokio::test]
async fn typed_async_reads_writes_and_read_many_against_the_simulator() {
    let sim = drivesim::Simulator::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../descriptions/lafert-smartris"
    ))
    .unwrap();
    sim.preset("bus_dc_link", 4950).unwrap();
    sim.preset("full_scale_velocity", 3000).unwrap();
    let server = sim.serve_modbus_tcp("127.0.0.1:0", UnitId(1)).unwrap();
    let client = AsyncTcpClient::connect(server.local_addr(), config())
        .await
        .unwrap();
    let mut drive = Smartris::modbus_async(client, UnitId(1));
    assert_eq!(drive.bus_dc_link().read().await, Ok(Volts(49.5)));
    let (status, volts, address) = drive
        .read_many_async((
            params::DriveStatus,
            params::BusDcLink,
            params::ModbusAddress,
        ))
        .await
        .unwrap();
    assert_eq!(status, DriveStatus::STANDBY);
    assert_eq!(volts, Volts(49.5));
    assert_eq!(address, 1);
    drive.speed_setpoint().write(Rpm(1500.0)).await.unwrap();
    assert_eq!(drive.speed_setpoint().read().await, Ok(Rpm(1500.0)));
    // The bound is read first and the value refused before it is sent, as the blocking API does.
    let beyond = drive.speed_setpoint().write(Rpm(3001.0)).await;
    assert_eq!(
        beyond,
        Err(Error::OutsideBound(OutsideBound {
            parameter: "speed_setpoint",
            bound: "full_scale_velocity",
            raw: 3001,
            limit: 3000,
        }))
    );
    assert_eq!(drive.speed_setpoint().read().await, Ok(Rpm(1500.0)));
    // The handle's futures are `Send`: a multi-threaded runtime can run them on any worker.
    let task = tokio::spawn(async move { drive.bus_dc_link().read().await });
    assert_eq!(task.await.unwrap(), Ok(Volts(49.5)));
}

#[path = "support/pymodbus_server.rs"]
mod pymodbus_server;

#[tokio::test]
async fn typed_async_api_against_pymodbus() {
    let server = pymodbus_server::start_server();
    let client = AsyncTcpClient::connect(&server.address, config())
        .await
        .expect("connect to pymodbus");
    let mut drive = Smartris::modbus_async(client, UnitId(1));
    // The server's input registers hold 0x1000 + address.
    let status = drive.drive_status().read().await.unwrap();
    assert_eq!(status.bits(), 0x1060, "undocumented bits survive");
    assert_eq!(drive.bus_dc_link().read().await, Ok(Volts(41.96)));
    assert_eq!(drive.axis_position().read_raw().await, Ok(0x1234_5678));
    let (status, warnings, error, volts) = drive
        .read_many_async((
            params::DriveStatus,
            params::WarningCode,
            params::ErrorCode,
            params::BusDcLink,
        ))
        .await
        .unwrap();
    assert_eq!(status.bits(), 0x1060);
    assert_eq!(warnings.bits(), 0x1062_1061);
    assert_eq!((error.raw(), error.is_known()), (0x1063, false));
    assert_eq!(volts, Volts(41.96));
    assert_eq!(drive.modbus_address().read().await, Ok(1));
    drive.modbus_address().write(2).await.unwrap();
    assert_eq!(drive.modbus_address().read().await, Ok(2));
    let run = ControlWord::RUN | ControlWord::STOP_DISABLED;
    drive.control_word().write(run).await.unwrap();
    assert_eq!(drive.control_word().read().await, Ok(run));
    drive.speed_setpoint().write(Rpm(3000.0)).await.unwrap();
}

#[tokio::test]
async fn typed_async_api_over_rtu_over_tcp_against_pymodbus() {
    let server = pymodbus_server::start_mode("rtu-over-tcp", &[]);
    let client = AsyncRtuClient::connect(&server.address, config())
        .await
        .expect("connect to pymodbus");
    let mut drive = Smartris::modbus_async(client, UnitId(1));
    assert_eq!(drive.bus_dc_link().read().await, Ok(Volts(41.96)));
    assert_eq!(drive.axis_position().read_raw().await, Ok(0x1234_5678));
    drive.modbus_address().write(2).await.unwrap();
    assert_eq!(drive.modbus_address().read().await, Ok(2));
    let (status, volts) = drive
        .read_many_async((params::DriveStatus, params::BusDcLink))
        .await
        .unwrap();
    assert_eq!((status.bits(), volts), (0x1060, Volts(41.96)));
}

#[tokio::test]
async fn the_run_sequence_awaited_sends_what_the_blocking_walk_sends() {
    const LIMIT: Duration = Duration::from_secs(3);
    let simulated = || {
        let sim = drivesim::Simulator::load(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../descriptions/lafert-smartris"
        ))
        .unwrap();
        let server = sim.serve_modbus_tcp("127.0.0.1:0", UnitId(1)).unwrap();
        (sim, server)
    };
    // The blocking walk standby → run → standby (Table 3: T2, T3), on one simulated drive.
    let (_sim, server) = simulated();
    let client = ModbusTcpClient::connect(server.local_addr(), &TcpConfig::default()).unwrap();
    let link = Smartris::modbus(client, UnitId(1)).into_link();
    let mut blocking = Smartris::new(Recorded::new(link));
    let deadline = || std::time::Instant::now() + LIMIT;
    assert_eq!(blocking.modbus_run_state(), Ok(Some(State::Standby)));
    blocking.goto_modbus_run(State::Run, deadline()).unwrap();
    assert_eq!(blocking.modbus_run_state(), Ok(Some(State::Run)));
    blocking
        .goto_modbus_run(State::Standby, deadline())
        .unwrap();
    assert_eq!(blocking.modbus_run_state(), Ok(Some(State::Standby)));

    // The same walk awaited, on a second simulated drive in the same state.
    let (_sim, server) = simulated();
    let client = AsyncTcpClient::connect(server.local_addr(), config())
        .await
        .unwrap();
    let link = Smartris::modbus_async(client, UnitId(1)).into_link().0;
    let mut drive = Smartris::new(Async(Recorded::new(link)));
    let timer = TokioTimer;
    drive
        .goto_modbus_run_async(State::Run, &timer, LIMIT)
        .await
        .unwrap();
    assert_eq!(drive.modbus_run_state_async().await, Ok(Some(State::Run)));
    drive
        .goto_modbus_run_async(State::Standby, &timer, LIMIT)
        .await
        .unwrap();
    assert_eq!(
        drive.modbus_run_state_async().await,
        Ok(Some(State::Standby))
    );

    // The same requests in the same order; the commands among them are the manual's run
    // (0x0003) and standby (0x0002).
    let sent = drive.device().link_mut().0.log_without_repeats();
    assert_eq!(sent, blocking.device().link_mut().log_without_repeats());
    let commands: Vec<&[u8]> = sent
        .iter()
        .filter_map(|request| match request {
            LinkRequest::Write(_, bytes) => Some(bytes.as_slice()),
            LinkRequest::Read(_) => None,
        })
        .collect();
    assert_eq!(commands, [[0x03, 0], [0x02, 0]]);
}
