//! Many simulated Modbus TCP drives polled from one process through the generated async Lafert
//! API (issue 30, "Scale"): reads per second, p99 latency and resident memory, sampled over the
//! run so that growth shows.
//!
//! `cargo run --release -p benchmarks --bin async-scale -- [--drives 1000] [--seconds 600]
//! [--period-ms 100] [--sample-s 10] [--workers 0]`
//!
//! Every drive gets its own connection (`AsyncTcpClient`) and `Smartris::modbus_async` handle,
//! and a task that reads `bus_dc_link` every `period-ms` (a tick that is missed is delayed,
//! not made up). The drives are served by `mbap-sim` in another process, so the CPU time and
//! memory reported are the client's. `--workers 0` (the default) runs a current-thread tokio
//! runtime; `--workers N` a multi-thread one with N workers. Prints Markdown.

use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use benchmarks::flags::Flags;
use benchmarks::latency::Histogram;
use benchmarks::process::{load_average, process_cpu, resident_bytes, Simulator};
use drivebus::modbus::async_client::{AsyncClientConfig, AsyncTcpClient};
use drivebus::modbus::UnitId;
use lafert_smartris::Smartris;
use tokio::time::MissedTickBehavior;

/// The run's settings, from the command line.
#[derive(Debug, Clone, Copy)]
struct Settings {
    drives: usize,
    seconds: u64,
    period: Duration,
    sample: Duration,
    workers: usize,
}

fn settings() -> Result<Settings, String> {
    let mut flags = Flags::from_env()?;
    let settings = Settings {
        drives: flags.number("--drives", 1000)? as usize,
        seconds: flags.number("--seconds", 600)?,
        period: Duration::from_millis(flags.number("--period-ms", 100)?),
        sample: Duration::from_secs(flags.number("--sample-s", 10)?.max(1)),
        workers: flags.number("--workers", 0)? as usize,
    };
    flags.finish()?;
    Ok(settings)
}

/// What the drives' tasks count, taken by the sampler every `sample`.
#[derive(Default)]
struct Window {
    latencies: Histogram,
    errors: u64,
}

async fn poll(addr: String, settings: Settings, offset: Duration, window: Arc<Mutex<Window>>) {
    let config = AsyncClientConfig::default();
    let client = match AsyncTcpClient::connect(addr.as_str(), config).await {
        Ok(client) => client,
        Err(e) => {
            eprintln!("{addr}: {e}");
            return;
        }
    };
    let mut drive = Smartris::modbus_async(client, UnitId(1));
    let start = tokio::time::Instant::now() + offset;
    let mut ticks = tokio::time::interval_at(start, settings.period);
    ticks.set_missed_tick_behavior(MissedTickBehavior::Delay);
    loop {
        ticks.tick().await;
        let sent = Instant::now();
        let read = drive.bus_dc_link().read().await;
        let latency = sent.elapsed();
        let mut window = window.lock().unwrap_or_else(|e| e.into_inner());
        match read {
            Ok(_) => window.latencies.record(latency),
            Err(_) => window.errors += 1,
        }
    }
}

fn mib(bytes: u64) -> f64 {
    bytes as f64 / (1024.0 * 1024.0)
}

fn ms(d: Option<Duration>) -> String {
    d.map_or_else(
        || "> 1000".into(),
        |d| format!("{:.2}", d.as_secs_f64() * 1e3),
    )
}

async fn run(settings: Settings, sim: &Simulator) {
    let window = Arc::new(Mutex::new(Window::default()));
    let spread = settings.period.as_nanos() as u64 / settings.drives.max(1) as u64;
    for (i, addr) in sim.addrs.iter().enumerate() {
        let offset = Duration::from_nanos(spread * i as u64);
        tokio::spawn(poll(addr.clone(), settings, offset, window.clone()));
    }
    println!(
        "| t (s) | reads/s | p99 ms | errors | resident MiB | client CPU % of one core | load average |"
    );
    println!("| ---: | ---: | ---: | ---: | ---: | ---: | --- |");
    let (begin, cpu0) = (Instant::now(), process_cpu());
    let mut overall = Histogram::default();
    // The spare window swapped in at each sample (emptied after): no allocation per sample.
    let mut taken = Window::default();
    let mut errors = 0;
    let mut rss = Vec::with_capacity(1024);
    let (mut last, mut last_cpu) = (begin, cpu0);
    let mut sample = tokio::time::interval_at(
        tokio::time::Instant::now() + settings.sample,
        settings.sample,
    );
    while begin.elapsed() < Duration::from_secs(settings.seconds) {
        sample.tick().await;
        std::mem::swap(
            &mut taken,
            &mut *window.lock().unwrap_or_else(|e| e.into_inner()),
        );
        let (now, cpu) = (Instant::now(), process_cpu());
        let span = (now - last).as_secs_f64();
        let resident = resident_bytes();
        rss.push(resident);
        println!(
            "| {:.0} | {:.0} | {} | {} | {:.1} | {:.0} | {} |",
            (now - begin).as_secs_f64(),
            taken.latencies.total() as f64 / span,
            ms(taken.latencies.quantile(0.99)),
            taken.errors,
            mib(resident),
            (cpu - last_cpu).as_secs_f64() / span * 100.0,
            load_average()
        );
        (last, last_cpu) = (now, cpu);
        errors += std::mem::take(&mut taken.errors);
        overall.drain_into(&mut taken.latencies);
    }
    let elapsed = begin.elapsed().as_secs_f64();
    let cpu = (process_cpu() - cpu0).as_secs_f64();
    let (first, peak) = (
        rss.first().copied().unwrap_or(0),
        rss.iter().max().copied().unwrap_or(0),
    );
    println!(
        "\n{} drives, {:.0} s, one read of `bus_dc_link` per drive every {} ms, {} runtime: \
         {:.0} reads/s, p50 {} ms, p99 {} ms, {errors} errors; client CPU {:.1} µs per read \
         ({:.0} % of one core); resident {:.1} MiB at the first sample, {:.1} MiB at the last, \
         {:.1} MiB at most.",
        settings.drives,
        elapsed,
        settings.period.as_millis(),
        match settings.workers {
            0 => "current-thread".to_string(),
            n => format!("multi-thread ({n} workers)"),
        },
        overall.total() as f64 / elapsed,
        ms(overall.quantile(0.5)),
        ms(overall.quantile(0.99)),
        cpu / overall.total().max(1) as f64 * 1e6,
        cpu / elapsed * 100.0,
        mib(first),
        mib(rss.last().copied().unwrap_or(0)),
        mib(peak),
    );
}

fn main() -> Result<(), String> {
    let settings = settings()?;
    let exe: PathBuf = std::env::current_exe()
        .map_err(|e| e.to_string())?
        .with_file_name("mbap-sim");
    let sim = Simulator::start(&exe, settings.drives).map_err(|e| {
        format!(
            "{}: {e} (build it: cargo build -p benchmarks --bins)",
            exe.display()
        )
    })?;
    let runtime = match settings.workers {
        0 => tokio::runtime::Builder::new_current_thread()
            .enable_all()
            .build(),
        n => tokio::runtime::Builder::new_multi_thread()
            .worker_threads(n)
            .enable_all()
            .build(),
    }
    .map_err(|e| e.to_string())?;
    println!("load average at the start: {}\n", load_average());
    runtime.block_on(run(settings, &sim));
    Ok(())
}
