//! Several drives on one Modbus line (issue 31 item 3): typed handles for units 1 to 4 on
//! clones of one `ModbusLine`, each in a thread or task of its own, against simulated drives
//! sharing the line (drivesim serving units 1 to 4 on one RTU byte stream; unit 5 is absent,
//! as a drive that is off), and against an independent implementation, pymodbus serving units
//! 1 to 4 of a Lafert-like map on one RTU line (tests/peers/modbus_server.py `--units`). Every
//! value read is checked against the drive it came from. The same four tasks also share one
//! pipelined Modbus TCP connection (`TokioPipeline`, issue 30 item 5), to the drivesim gateway and
//! to pyModbusTCP (tests/peers/pipelining_server.py), their requests in flight at once.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Barrier};
use std::thread;
use std::time::Duration;

use drivebus::modbus::async_client::{AsyncClientConfig, AsyncRtuClient, AsyncTcpClient};
use drivebus::modbus::client::{SerialConfig, SerialRtuClient};
use drivebus::modbus::pipeline::TokioPipeline;
use drivebus::modbus::retry::RetryPolicy;
use drivebus::modbus::{AsyncRegisterBus, ModbusLine, Table, UnitId};
use drivebus::units::{Rpm, Volts};
use drivebus::BusError;
use drivesim::modbus::tcp::TcpServer;
use drivesim::modbus::Units;
use drivesim::Simulator;
use lafert_smartris::Smartris;

const UNITS: [u8; 4] = [1, 2, 3, 4];
/// No drive answers at this id.
const ABSENT: u8 = 5;

fn description() -> &'static str {
    concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../descriptions/lafert-smartris"
    )
}

/// The DC link voltage unit `unit`'s drive reports, in 1/100 V: a different one per drive.
fn dc_link_raw(unit: u8) -> i128 {
    4000 + 100 * i128::from(unit)
}

/// A simulated drive per unit id, each with its own DC link voltage.
fn drives() -> Units {
    Units::new(UNITS.map(|unit| {
        let sim = Simulator::load(description()).unwrap();
        sim.preset("bus_dc_link", dc_link_raw(unit)).unwrap();
        sim.preset("full_scale_velocity", 3000).unwrap();
        (UnitId(unit), sim)
    }))
}

/// Reads, writes and reads back unit `unit`'s values `rounds` times through `drive`.
fn exercise<B: drivebus::modbus::RegisterBus>(
    drive: &mut Smartris<drivebus::modbus::ModbusLink<B>>,
    unit: u8,
    rounds: i16,
) {
    for round in 0..rounds {
        assert_eq!(
            drive.bus_dc_link().read(),
            Ok(Volts(dc_link_raw(unit) as f64 / 100.0)),
            "unit {unit}'s own drive answered"
        );
        let speed = f64::from(i16::from(unit) * 100 + round);
        drive.speed_setpoint().write(Rpm(speed)).unwrap();
        assert_eq!(drive.speed_setpoint().read(), Ok(Rpm(speed)), "unit {unit}");
    }
}

#[test]
fn four_drives_on_one_rtu_line_from_four_threads_and_a_silent_unit() {
    let pty = peer_support::pty_pair();
    let server_path = pty.server.to_str().unwrap().to_owned();
    let config = SerialConfig {
        // Ample: the simulator thread may wait for a core while the other tests run.
        timeout: Duration::from_millis(300),
        retry: RetryPolicy::NONE,
        ..SerialConfig::new(115_200)
    };
    let mut stream = drivebus::modbus::client::SerialStream::open(&server_path, &config).unwrap();
    let units = drives();
    // Ends with an I/O error when the pty pair goes away at the end of the test.
    thread::spawn(move || drivesim::modbus::rtu::serve_units(&units, &mut stream));
    let client = SerialRtuClient::open(pty.client.to_str().unwrap(), &config).unwrap();
    let line = ModbusLine::new(client);
    let silent = {
        let line = line.clone();
        thread::spawn(move || {
            let mut off = Smartris::modbus(line, UnitId(ABSENT));
            for _ in 0..3 {
                let read = off.bus_dc_link().read();
                assert_eq!(read.unwrap_err().bus(), Some(&BusError::Timeout));
            }
        })
    };
    let threads: Vec<_> = UNITS
        .map(|unit| {
            let line = line.clone();
            thread::spawn(move || exercise(&mut Smartris::modbus(line, UnitId(unit)), unit, 8))
        })
        .into();
    for thread in threads {
        thread
            .join()
            .expect("every request of units 1-4 answered, despite unit 5");
    }
    silent.join().expect("each of unit 5's requests timed out");
}

#[test]
fn units_polling_one_line_in_tight_loops_each_get_their_share() {
    let server = TcpServer::gateway(drives(), "127.0.0.1:0").unwrap();
    let client = drivebus::modbus::client::ModbusTcpClient::connect(
        server.local_addr(),
        &drivebus::modbus::client::TcpConfig::default(),
    )
    .unwrap();
    let line = ModbusLine::new(client);
    let start = Arc::new(Barrier::new(UNITS.len()));
    let stop = Arc::new(AtomicBool::new(false));
    let threads: Vec<_> = UNITS
        .map(|unit| {
            let (line, start, stop) = (line.clone(), Arc::clone(&start), Arc::clone(&stop));
            thread::spawn(move || {
                let mut drive = Smartris::modbus(line, UnitId(unit));
                let expected = Ok(Volts(dc_link_raw(unit) as f64 / 100.0));
                let mut completed = 0u32;
                start.wait();
                while !stop.load(Ordering::Relaxed) {
                    assert_eq!(drive.bus_dc_link().read(), expected);
                    completed += 1;
                }
                completed
            })
        })
        .into();
    thread::sleep(Duration::from_millis(500));
    stop.store(true, Ordering::Relaxed);
    let completed: Vec<u32> = threads.into_iter().map(|t| t.join().unwrap()).collect();
    let most = completed.iter().copied().max().unwrap();
    // Served in turn: no unit gets much less than another (a scheduler's hiccup costs a few).
    assert!(
        completed.iter().all(|&n| n >= 5 && 2 * n >= most),
        "completed requests per unit: {completed:?}"
    );
}

fn async_config() -> AsyncClientConfig {
    AsyncClientConfig {
        timeout: Duration::from_millis(200),
        retry: RetryPolicy::NONE,
        ..AsyncClientConfig::default()
    }
}

/// Runs `work` for each unit from a task of its own over `line` (a `ModbusLine`, or a pipelined
/// connection), and reads the absent unit meanwhile: every unit's work completes, and only the
/// absent unit's read times out.
async fn tasks_share<B, W, F>(line: B, work: W)
where
    B: drivebus::modbus::AsyncRegisterBus + Clone + 'static,
    W: Fn(B, u8) -> F,
    F: std::future::Future<Output = ()> + 'static,
{
    let local = tokio::task::LocalSet::new();
    local
        .run_until(async move {
            let absent = {
                let line = line.clone();
                tokio::task::spawn_local(async move {
                    let mut off = Smartris::modbus_async(line, UnitId(ABSENT));
                    off.bus_dc_link().read().await
                })
            };
            let tasks: Vec<_> = UNITS
                .map(|unit| tokio::task::spawn_local(work(line.clone(), unit)))
                .into();
            for task in tasks {
                task.await.expect("every request of units 1-4 answered");
            }
            let absent = absent.await.unwrap().unwrap_err();
            assert_eq!(
                absent.bus(),
                Some(&BusError::Timeout),
                "only the absent unit's request timed out"
            );
        })
        .await;
}

/// Reads and writes unit `unit`'s values on the simulated drives, checking each.
async fn exercise_async<B: drivebus::modbus::AsyncRegisterBus>(line: B, unit: u8) {
    let mut drive = Smartris::modbus_async(line, UnitId(unit));
    for round in 0..10 {
        assert_eq!(
            drive.bus_dc_link().read().await,
            Ok(Volts(dc_link_raw(unit) as f64 / 100.0)),
            "unit {unit}"
        );
        let speed = f64::from(i16::from(unit) * 100 + round);
        drive.speed_setpoint().write(Rpm(speed)).await.unwrap();
        assert_eq!(drive.speed_setpoint().read().await, Ok(Rpm(speed)));
    }
}

#[tokio::test]
async fn four_drives_behind_one_rtu_gateway_from_four_tasks() {
    let addr = drivesim::modbus::rtu_over_tcp::serve_units(drives(), "127.0.0.1:0").unwrap();
    let client = AsyncRtuClient::connect(addr, async_config()).await.unwrap();
    tasks_share(ModbusLine::new(client), exercise_async).await;
}

#[tokio::test]
async fn four_drives_behind_one_modbus_tcp_gateway_from_four_tasks() {
    let server = TcpServer::gateway(drives(), "127.0.0.1:0").unwrap();
    let client = AsyncTcpClient::connect(server.local_addr(), async_config())
        .await
        .unwrap();
    tasks_share(ModbusLine::new(client), exercise_async).await;
}

#[tokio::test]
async fn four_drives_behind_one_modbus_tcp_gateway_pipelined_from_four_tasks() {
    let server = TcpServer::gateway(drives(), "127.0.0.1:0").unwrap();
    let pipeline = TokioPipeline::connect(server.local_addr(), &async_config())
        .await
        .unwrap();
    tasks_share(pipeline.clone(), exercise_async).await;
    assert_eq!(
        pipeline.in_flight(),
        0,
        "the absent unit's request gave up its slot"
    );
}

#[path = "support/pymodbus_server.rs"]
mod pymodbus_server;

/// Unit `unit`'s values on pymodbus, written and read back three times through `line`.
async fn exercise_pymodbus<B: drivebus::modbus::AsyncRegisterBus>(line: B, unit: u8) {
    let mut drive = Smartris::modbus_async(line, UnitId(unit));
    for _ in 0..3 {
        drive
            .modbus_address()
            .write(u16::from(unit) + 10)
            .await
            .unwrap();
        let volts = drive.bus_dc_link().read().await.unwrap();
        let address = drive.modbus_address().read().await;
        check_pymodbus_unit(unit, address, volts);
    }
}

#[tokio::test]
async fn four_handles_on_one_pipelined_connection_to_pymodbustcp_from_four_tasks() {
    // pyModbusTCP, an independent implementation that answers pipelined requests (pymodbus
    // 3.16.1 answers only the first frame of a segment); one register map for every unit id.
    let server = pymodbus_server::start_pipelining_server();
    let config = AsyncClientConfig {
        timeout: Duration::from_secs(2),
        ..async_config()
    };
    let pipeline = TokioPipeline::connect(&server.address, &config)
        .await
        .unwrap();
    let tasks: Vec<_> = UNITS
        .map(|unit| {
            let mut bus = pipeline.clone();
            tokio::spawn(async move {
                let register = 0x40 + u16::from(unit);
                for round in 0..10u16 {
                    // A typed read: input 0x0064 holds 0x1000 + 0x64 (41.96 V).
                    let mut drive = Smartris::modbus_async(bus.clone(), UnitId(unit));
                    assert_eq!(drive.bus_dc_link().read().await, Ok(Volts(41.96)));
                    // A register of this task's own, written and read back.
                    let value = 1000 * u16::from(unit) + round;
                    bus.write_register(UnitId(unit), register, value)
                        .await
                        .unwrap();
                    let mut back = [0u16];
                    bus.read_registers(UnitId(unit), Table::Holding, register, &mut back)
                        .await
                        .unwrap();
                    assert_eq!(back, [value], "unit {unit}, round {round}");
                }
            })
        })
        .into();
    for task in tasks {
        task.await.expect("every request answered");
    }
}

/// Unit `unit`'s pymodbus map: its own id in 0x0028 (`modbus_address`), the shared DC link
/// voltage in input 0x0064.
fn check_pymodbus_unit(unit: u8, address: Result<u16, drivebus::Error>, volts: Volts) {
    assert_eq!(
        address,
        Ok(u16::from(unit) + 10),
        "unit {unit}'s own register"
    );
    assert_eq!(volts, Volts(41.96), "unit {unit}");
}

#[test]
fn four_pymodbus_units_on_one_rtu_line_from_four_threads() {
    let pty = peer_support::pty_pair();
    let _server = peer_support::ready_peer(
        &peer_support::peers_dir().join("modbus_server.py"),
        &["rtu", pty.server.to_str().unwrap(), "--units", "1,2,3,4"],
    );
    let config = SerialConfig {
        timeout: Duration::from_millis(300),
        retry: RetryPolicy::NONE,
        ..SerialConfig::new(19_200)
    };
    let line =
        ModbusLine::new(SerialRtuClient::open(pty.client.to_str().unwrap(), &config).unwrap());
    let absent = {
        let line = line.clone();
        thread::spawn(move || Smartris::modbus(line, UnitId(ABSENT)).bus_dc_link().read())
    };
    let threads: Vec<_> = UNITS
        .map(|unit| {
            let line = line.clone();
            thread::spawn(move || {
                let mut drive = Smartris::modbus(line, UnitId(unit));
                for _ in 0..3 {
                    drive.modbus_address().write(u16::from(unit) + 10).unwrap();
                    let volts = drive.bus_dc_link().read().unwrap();
                    check_pymodbus_unit(unit, drive.modbus_address().read(), volts);
                }
            })
        })
        .into();
    for thread in threads {
        thread.join().expect("every request of units 1-4 answered");
    }
    let absent = absent.join().unwrap().unwrap_err();
    assert_eq!(absent.bus(), Some(&BusError::Timeout));
}

#[tokio::test]
async fn four_pymodbus_units_behind_one_rtu_gateway_from_four_tasks() {
    let server = pymodbus_server::start_mode("rtu-over-tcp", &["--units", "1,2,3,4"]);
    let config = AsyncClientConfig {
        timeout: Duration::from_millis(300),
        ..async_config()
    };
    let client = AsyncRtuClient::connect(&server.address, config)
        .await
        .unwrap();
    tasks_share(ModbusLine::new(client), exercise_pymodbus).await;
}
