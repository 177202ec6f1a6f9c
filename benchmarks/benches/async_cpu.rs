//! CPU per request, async against blocking (issue 30): the same loopback Modbus TCP workload —
//! the Lafert `bus_dc_link` (one input register) read again and again from a simulated drive in
//! another process (`mbap-sim`) — through
//!
//! * the generated Lafert handle over the blocking `ModbusTcpClient`;
//! * the generated Lafert handle over the async `AsyncTcpClient`, on a current-thread tokio
//!   runtime (`Smartris::modbus_async`);
//! * tokio-modbus 0.16's async client on the same runtime kind (`read_input_registers`).
//!
//! Process CPU time (`getrusage(RUSAGE_SELF)`, user + system) is the measure: the server runs in
//! its own process, so this is the client's alone, whatever the scheduler does with the wake-ups.
//! The variants alternate within each round (the order rotates) so other load on the machine hits
//! them alike. `cargo bench -p benchmarks --bench async_cpu [-- READS ROUNDS]`; prints Markdown.

use std::path::Path;
use std::time::{Duration, Instant};

use benchmarks::process::{load_average, process_cpu, Simulator};
use drivebus::modbus::async_client::{AsyncClientConfig, AsyncTcpClient};
use drivebus::modbus::client::{ModbusTcpClient, TcpConfig};
use drivebus::modbus::UnitId;
use drivebus::units::Volts;
use lafert_smartris::Smartris;

const UNIT: UnitId = UnitId(1);
/// `bus_dc_link`'s input register; the simulator answers 0x1000 + address.
const BUS_DC_LINK: u16 = 0x0064;
const EXPECTED: Volts = Volts((0x1000 + 0x64) as f64 / 100.0);

/// CPU and wall time per request of one variant in one round.
#[derive(Debug, Clone, Copy)]
struct PerRequest {
    cpu: Duration,
    wall: Duration,
}

fn measure(reads: u32, run: impl FnOnce()) -> PerRequest {
    let (wall, cpu) = (Instant::now(), process_cpu());
    run();
    PerRequest {
        cpu: (process_cpu() - cpu) / reads,
        wall: wall.elapsed() / reads,
    }
}

fn runtime() -> tokio::runtime::Runtime {
    tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .unwrap()
}

fn blocking(addr: &str, reads: u32) -> PerRequest {
    let client = ModbusTcpClient::connect(addr, &TcpConfig::default()).unwrap();
    let mut drive = Smartris::modbus(client, UNIT);
    measure(reads, || {
        for _ in 0..reads {
            assert_eq!(drive.bus_dc_link().read(), Ok(EXPECTED));
        }
    })
}

fn drivegen_async(addr: &str, reads: u32) -> PerRequest {
    let rt = runtime();
    let client = rt
        .block_on(AsyncTcpClient::connect(addr, AsyncClientConfig::default()))
        .unwrap();
    let mut drive = Smartris::modbus_async(client, UNIT);
    measure(reads, || {
        rt.block_on(async {
            for _ in 0..reads {
                assert_eq!(drive.bus_dc_link().read().await, Ok(EXPECTED));
            }
        })
    })
}

fn tokio_modbus(addr: &str, reads: u32) -> PerRequest {
    use tokio_modbus::client::Reader;
    let rt = runtime();
    let mut ctx = rt
        .block_on(tokio_modbus::client::tcp::connect_slave(
            addr.parse().unwrap(),
            tokio_modbus::Slave(UNIT.0),
        ))
        .unwrap();
    measure(reads, || {
        rt.block_on(async {
            for _ in 0..reads {
                let registers = ctx.read_input_registers(BUS_DC_LINK, 1).await;
                assert_eq!(registers.unwrap().unwrap(), [0x1064]);
            }
        })
    })
}

type Variant = (&'static str, fn(&str, u32) -> PerRequest);

const VARIANTS: [Variant; 3] = [
    ("drivegen blocking", blocking),
    ("drivegen async", drivegen_async),
    ("tokio-modbus", tokio_modbus),
];

fn us(d: Duration) -> f64 {
    d.as_nanos() as f64 / 1000.0
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    // `cargo bench` passes `--bench`; numbers among the arguments are READS then ROUNDS.
    let numbers: Vec<u32> = std::env::args().filter_map(|a| a.parse().ok()).collect();
    let reads = numbers.first().copied().unwrap_or(20_000);
    let rounds = numbers.get(1).copied().unwrap_or(5) as usize;
    let sim = Simulator::start(Path::new(env!("CARGO_BIN_EXE_mbap-sim")), 1).unwrap();
    let addr = &sim.addrs[0];
    // `ASYNC_CPU_ONLY=<variant index>`: that variant alone, once, nothing printed; for counting
    // its system calls and wake-ups per read (`strace -c`, `perf stat`), the server aside.
    if let Some(only) = std::env::var("ASYNC_CPU_ONLY")
        .ok()
        .and_then(|i| i.parse::<usize>().ok())
    {
        VARIANTS[only.min(VARIANTS.len() - 1)].1(addr, reads);
        return;
    }
    let load_before = load_average();
    // One warm-up read loop each (connections, page faults, the server's first task).
    for (_, variant) in VARIANTS {
        variant(addr, 1000);
    }
    let mut results = vec![Vec::new(); VARIANTS.len()];
    for round in 0..rounds {
        for k in 0..VARIANTS.len() {
            let i = (round + k) % VARIANTS.len();
            results[i].push(VARIANTS[i].1(addr, reads));
        }
    }
    println!(
        "{reads} reads per variant and round, {rounds} rounds; load average before {load_before}, \
         after {}\n",
        load_average()
    );
    println!("| variant | process CPU µs/read, per round | median | wall µs/read, median |");
    println!("| --- | --- | ---: | ---: |");
    for ((name, _), rounds) in VARIANTS.iter().zip(&results) {
        let cpus: Vec<f64> = rounds.iter().map(|r| us(r.cpu)).collect();
        let listed: Vec<String> = cpus.iter().map(|c| format!("{c:.1}")).collect();
        let wall = median(rounds.iter().map(|r| us(r.wall)).collect());
        println!(
            "| {name} | {} | {:.1} | {wall:.1} |",
            listed.join(", "),
            median(cpus.clone())
        );
    }
    let ratio = |a: usize, b: usize| -> Vec<f64> {
        results[a]
            .iter()
            .zip(&results[b])
            .map(|(x, y)| us(x.cpu) / us(y.cpu))
            .collect()
    };
    println!("\n| ratio of process CPU per read | per round | median |");
    println!("| --- | --- | ---: |");
    for (name, ratios) in [
        ("async / blocking (target ≤ 1.1)", ratio(1, 0)),
        ("async / tokio-modbus (target ≤ 1)", ratio(1, 2)),
        ("tokio-modbus / blocking", ratio(2, 0)),
    ] {
        let listed: Vec<String> = ratios.iter().map(|r| format!("{r:.2}")).collect();
        println!("| {name} | {} | {:.2} |", listed.join(", "), median(ratios));
    }
}
