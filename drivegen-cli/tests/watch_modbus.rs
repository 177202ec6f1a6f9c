//! `drivegen watch` over Modbus TCP reads each interval with the planner's fewest requests: a
//! proxy between the CLI and the simulated Lafert counts the requests, and the count per sample
//! equals the length of `drivebus::modbus::planner::plan` for the watched parameters. The CSV
//! output carries the same values.

use std::io::{Read, Write};
use std::net::{SocketAddr, TcpListener, TcpStream};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use std::thread;

use drivebus::modbus::planner;
use drivebus::modbus::UnitId;
use drivesim::Simulator;

const BIN: &str = env!("CARGO_BIN_EXE_drivegen");

fn lafert() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../descriptions/lafert-smartris")
}

/// A proxy to `server` that counts the Modbus TCP requests (MBAP frames) passing through it.
fn counting_proxy(server: SocketAddr) -> (String, Arc<AtomicUsize>) {
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let addr = listener.local_addr().unwrap().to_string();
    let requests = Arc::new(AtomicUsize::new(0));
    let counted = Arc::clone(&requests);
    thread::spawn(move || {
        for client in listener.incoming() {
            let Ok(mut client) = client else { return };
            let mut upstream = TcpStream::connect(server).unwrap();
            let (mut answers, mut back) =
                (upstream.try_clone().unwrap(), client.try_clone().unwrap());
            thread::spawn(move || std::io::copy(&mut answers, &mut back));
            let counted = Arc::clone(&counted);
            thread::spawn(move || forward_requests(&mut client, &mut upstream, &counted));
        }
    });
    (addr, requests)
}

/// Copies request frames from `client` to `upstream`, counting them, until the client closes.
fn forward_requests(client: &mut TcpStream, upstream: &mut TcpStream, counted: &AtomicUsize) {
    let mut header = [0u8; 7];
    while client.read_exact(&mut header).is_ok() {
        let len = usize::from(u16::from_be_bytes([header[4], header[5]]));
        let mut pdu = vec![0u8; len.saturating_sub(1)];
        if client.read_exact(&mut pdu).is_err() {
            return;
        }
        counted.fetch_add(1, Ordering::SeqCst);
        if upstream
            .write_all(&header)
            .and_then(|()| upstream.write_all(&pdu))
            .is_err()
        {
            return;
        }
    }
}

#[test]
fn each_sample_takes_the_planners_requests_and_csv_shows_it() {
    let sim = Simulator::load(lafert()).unwrap();
    sim.preset("bus_dc_link", 4950).unwrap();
    sim.preset("operation_mode", 2).unwrap();
    let server = sim.serve_modbus_tcp("127.0.0.1:0", UnitId(1)).unwrap();
    let (proxy, requests) = counting_proxy(server.local_addr());
    let names = [
        "bus_dc_link",
        "drive_status",
        "operation_mode",
        "velocity_average",
    ];
    let device = drivegen::check(&lafert()).device.unwrap();
    let addresses: Vec<_> = names
        .iter()
        .map(|n| *device.parameter(n).unwrap().modbus[0])
        .collect();
    let planned = planner::plan(&device.modbus_limits(), &addresses)
        .unwrap()
        .len();
    assert!(planned < names.len(), "the planner merges: {planned}");
    let samples = 3;
    let count = samples.to_string();
    let output = Command::new(BIN)
        .arg("watch")
        .arg(lafert())
        .args(names)
        .args([
            "--modbus-tcp",
            &proxy,
            "--count",
            &count,
            "--interval-ms",
            "10",
            "--csv",
        ])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert_eq!(
        requests.load(Ordering::SeqCst),
        samples * planned,
        "{stdout}"
    );
    let mut lines = stdout.lines();
    assert_eq!(
        lines.next(),
        Some("time [s],bus_dc_link [V],drive_status,operation_mode,velocity_average [rpm]"),
        "{stdout}"
    );
    let rows: Vec<&str> = lines.collect();
    assert_eq!(rows.len(), samples, "{stdout}");
    for row in rows {
        assert!(row.contains(",49.5,standby,velocity,"), "{stdout}");
    }
}
