//! N units on one Modbus line against one unit (issue 31): the same loopback Modbus TCP
//! workload — the Lafert `bus_dc_link` (one input register) read again and again from a
//! simulated gateway in another process (`mbap-sim`, which answers every unit id) — through
//!
//! * one handle on the blocking `ModbusTcpClient` itself, N·R reads (`one unit, own client`);
//! * one handle on a `ModbusLine` over that client, N·R reads (`one unit, line`): what the
//!   line's fair queue costs;
//! * N handles, units 1..=N, each in its own thread on clones of one `ModbusLine`, R reads each
//!   (`N units, N threads, line`);
//! * the async twins: one task on the `AsyncTcpClient`, and N tasks on clones of one
//!   `ModbusLine` over it, on a current-thread tokio runtime;
//! * N tasks on clones of one `TokioPipeline` (issue 30 item 5): their requests in flight at
//!   once on one connection; printed also as a ratio to the N tasks through the line.
//!
//! A line carries one request at a time, so N units cannot beat one unit's rate: the target is
//! the same time per read (ratio 1), i.e. sharing costs nothing. Wall and process CPU time per
//! read; the variants alternate within each round (the order rotates), so other load hits them
//! alike. `cargo bench -p benchmarks --bench modbus_line [-- READS ROUNDS UNITS]`; prints
//! Markdown.

use std::path::Path;
use std::time::{Duration, Instant};

use benchmarks::process::{load_average, process_cpu, Simulator};
use drivebus::modbus::async_client::{AsyncClientConfig, AsyncTcpClient};
use drivebus::modbus::client::{ModbusTcpClient, TcpConfig};
use drivebus::modbus::pipeline::TokioPipeline;
use drivebus::modbus::{ModbusLine, UnitId};
use drivebus::units::Volts;
use lafert_smartris::Smartris;

/// `bus_dc_link`'s input register holds 0x1064 on the simulator (0x1000 + address).
const EXPECTED: Volts = Volts((0x1000 + 0x64) as f64 / 100.0);

/// CPU and wall time per read of one variant in one round.
#[derive(Debug, Clone, Copy)]
struct PerRead {
    cpu: Duration,
    wall: Duration,
}

/// What one variant is given: the gateway, the reads per unit and the unit count.
#[derive(Debug, Clone, Copy)]
struct Load<'a> {
    addr: &'a str,
    reads: u32,
    units: u8,
}

impl Load<'_> {
    fn total(&self) -> u32 {
        self.reads * u32::from(self.units)
    }

    fn measure(&self, run: impl FnOnce()) -> PerRead {
        let (wall, cpu) = (Instant::now(), process_cpu());
        run();
        PerRead {
            cpu: (process_cpu() - cpu) / self.total(),
            wall: wall.elapsed() / self.total(),
        }
    }
}

fn client(addr: &str) -> ModbusTcpClient {
    ModbusTcpClient::connect(addr, &TcpConfig::default()).unwrap()
}

fn own_client(load: Load<'_>) -> PerRead {
    let mut drive = Smartris::modbus(client(load.addr), UnitId(1));
    load.measure(|| {
        for _ in 0..load.total() {
            assert_eq!(drive.bus_dc_link().read(), Ok(EXPECTED));
        }
    })
}

fn one_on_line(load: Load<'_>) -> PerRead {
    let mut drive = Smartris::modbus(ModbusLine::new(client(load.addr)), UnitId(1));
    load.measure(|| {
        for _ in 0..load.total() {
            assert_eq!(drive.bus_dc_link().read(), Ok(EXPECTED));
        }
    })
}

fn threads_on_line(load: Load<'_>) -> PerRead {
    let line = ModbusLine::new(client(load.addr));
    load.measure(|| {
        std::thread::scope(|scope| {
            for unit in 1..=load.units {
                let mut drive = Smartris::modbus(line.clone(), UnitId(unit));
                scope.spawn(move || {
                    for _ in 0..load.reads {
                        assert_eq!(drive.bus_dc_link().read(), Ok(EXPECTED));
                    }
                });
            }
        });
    })
}

fn runtime() -> tokio::runtime::Runtime {
    tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .unwrap()
}

fn async_client(
    rt: &tokio::runtime::Runtime,
    addr: &str,
) -> AsyncTcpClient<drivebus::modbus::async_client::tokio::TokioTcp, drivebus::asynch::TokioTimer> {
    rt.block_on(AsyncTcpClient::connect(addr, AsyncClientConfig::default()))
        .unwrap()
}

fn async_own_client(load: Load<'_>) -> PerRead {
    let rt = runtime();
    let mut drive = Smartris::modbus_async(async_client(&rt, load.addr), UnitId(1));
    load.measure(|| {
        rt.block_on(async {
            for _ in 0..load.total() {
                assert_eq!(drive.bus_dc_link().read().await, Ok(EXPECTED));
            }
        })
    })
}

fn tasks_on_line(load: Load<'_>) -> PerRead {
    let rt = runtime();
    let line = ModbusLine::new(async_client(&rt, load.addr));
    tasks_sharing(&rt, line, load)
}

fn tasks_pipelined(load: Load<'_>) -> PerRead {
    let rt = runtime();
    let pipeline = rt
        .block_on(TokioPipeline::connect(
            load.addr,
            &AsyncClientConfig::default(),
        ))
        .unwrap();
    tasks_sharing(&rt, pipeline, load)
}

/// Units 1..=N, each a task on its own clone of `bus`, R reads each; local tasks on the
/// current-thread runtime (a generic bus's futures are not known to be `Send`).
fn tasks_sharing<B>(rt: &tokio::runtime::Runtime, bus: B, load: Load<'_>) -> PerRead
where
    B: drivebus::modbus::AsyncRegisterBus + Clone + 'static,
{
    let local = tokio::task::LocalSet::new();
    load.measure(|| {
        local.block_on(rt, async {
            let tasks: Vec<_> = (1..=load.units)
                .map(|unit| {
                    let mut drive = Smartris::modbus_async(bus.clone(), UnitId(unit));
                    tokio::task::spawn_local(async move {
                        for _ in 0..load.reads {
                            assert_eq!(drive.bus_dc_link().read().await, Ok(EXPECTED));
                        }
                    })
                })
                .collect();
            for task in tasks {
                task.await.unwrap();
            }
        })
    })
}

type Variant = (&'static str, fn(Load<'_>) -> PerRead);

const VARIANTS: [Variant; 6] = [
    ("one unit, own client", own_client),
    ("one unit, line", one_on_line),
    ("N units, N threads, line", threads_on_line),
    ("async: one unit, own client", async_own_client),
    ("async: N units, N tasks, line", tasks_on_line),
    ("async: N units, N tasks, pipelined", tasks_pipelined),
];

/// The index of the async N tasks serialised through a line.
const LINE_TASKS: usize = 4;
/// The index of the async N tasks pipelined on one connection.
const PIPELINED_TASKS: usize = 5;

fn us(d: Duration) -> f64 {
    d.as_nanos() as f64 / 1000.0
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// The per-round ratios of variant `i` to the blocking (or, for async, the async) own client.
fn ratios(results: &[Vec<PerRead>], i: usize) -> Vec<f64> {
    let base = if i < 3 { 0 } else { 3 };
    results[i]
        .iter()
        .zip(&results[base])
        .map(|(v, b)| us(v.wall) / us(b.wall))
        .collect()
}

fn main() {
    // `cargo bench` passes `--bench`; numbers among the arguments are READS, ROUNDS, UNITS.
    let numbers: Vec<u32> = std::env::args().filter_map(|a| a.parse().ok()).collect();
    let reads = numbers.first().copied().unwrap_or(5_000);
    let rounds = numbers.get(1).copied().unwrap_or(5) as usize;
    let units = numbers.get(2).copied().unwrap_or(4).clamp(1, 247) as u8;
    let sim = Simulator::start(Path::new(env!("CARGO_BIN_EXE_mbap-sim")), 1).unwrap();
    let load = Load {
        addr: &sim.addrs[0],
        reads,
        units,
    };
    let load_before = load_average();
    // One warm-up loop each (connections, page faults, the server's first task).
    for (_, variant) in VARIANTS {
        variant(Load { reads: 200, ..load });
    }
    let mut results = vec![Vec::new(); VARIANTS.len()];
    for round in 0..rounds {
        for k in 0..VARIANTS.len() {
            let i = (round + k) % VARIANTS.len();
            results[i].push(VARIANTS[i].1(load));
        }
    }
    println!(
        "N = {units} units, {} reads per variant and round, {rounds} rounds; load average \
         before {load_before}, after {}\n",
        load.total(),
        load_average()
    );
    println!("| variant | wall µs/read, median | CPU µs/read, median | wall / own client, per round | median |");
    println!("| --- | ---: | ---: | --- | ---: |");
    for (i, (name, _)) in VARIANTS.iter().enumerate() {
        let wall = median(results[i].iter().map(|r| us(r.wall)).collect());
        let cpu = median(results[i].iter().map(|r| us(r.cpu)).collect());
        let per_round = ratios(&results, i);
        let shown: Vec<String> = per_round.iter().map(|r| format!("{r:.2}")).collect();
        println!(
            "| {name} | {wall:.1} | {cpu:.1} | {} | **{:.2}** |",
            shown.join(", "),
            median(per_round)
        );
    }
    // Pipelining across handles (issue 30 item 5): the same N tasks, their requests in flight
    // at once on one connection instead of one after the other through a line.
    let pipelined: Vec<f64> = results[PIPELINED_TASKS]
        .iter()
        .zip(&results[LINE_TASKS])
        .map(|(p, l)| us(p.wall) / us(l.wall))
        .collect();
    let shown: Vec<String> = pipelined.iter().map(|r| format!("{r:.2}")).collect();
    println!(
        "\nwall per read, N tasks pipelined / N tasks through a line, per round: {}; median **{:.2}**",
        shown.join(", "),
        median(pipelined)
    );
}
