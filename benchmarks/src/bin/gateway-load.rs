//! Many simulated drives through one `drivegen gateway` to a local mosquitto (issue 35,
//! "Performance"): messages per second at the subscriber, end-to-end latency from the drive's
//! answer to the subscriber (p50 / p99), and the gateway's CPU and resident memory, sampled over
//! the run so that growth shows.
//!
//! `cargo build --release -p drivegen-cli -p benchmarks --bins && target/release/gateway-load
//! [--drives 100] [--seconds 600] [--period-ms 100] [--sample-s 10]`
//!
//! Each drive is a Lafert description polled for 10 parameters (`drive_status` to `i2t_energy`,
//! one Modbus request) every `period-ms`, every value published at every poll
//! (`publish_every_poll`), so 100 drives at 100 ms offer 10,000 messages/s. The drives are
//! `mbap-sim` in its own process, the broker is mosquitto (started here on a free loopback
//! port), the subscriber is `mosquitto_sub`. A payload's `time` has millisecond resolution, so
//! latencies read up to 1 ms high. Prints Markdown.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant, SystemTime};

use benchmarks::flags::Flags;
use benchmarks::latency::Histogram;
use benchmarks::process::{load_average, other_process_cpu, other_resident_bytes, Simulator};
use peer_support::{mosquitto, Process};

/// The ten parameters each drive publishes: input registers 0x60-0x6A, one request.
const PARAMETERS: [&str; 10] = [
    "drive_status",
    "warning_code",
    "error_code",
    "bus_dc_link",
    "motor_temperature",
    "heat_sink_temperature",
    "board_temperature",
    "velocity_average",
    "torque_current",
    "i2t_energy",
];

#[derive(Debug, Clone, Copy)]
struct Settings {
    drives: usize,
    seconds: u64,
    period_ms: u64,
    sample: Duration,
}

fn settings() -> Result<Settings, String> {
    let mut flags = Flags::from_env()?;
    let settings = Settings {
        drives: flags.number("--drives", 100)? as usize,
        seconds: flags.number("--seconds", 600)?,
        period_ms: flags.number("--period-ms", 100)?.max(1),
        sample: Duration::from_secs(flags.number("--sample-s", 10)?.max(1)),
    };
    flags.finish()?;
    Ok(settings)
}

fn gateway_file(dir: &Path, port: u16, settings: &Settings, addrs: &[String]) -> PathBuf {
    let lafert = Path::new(env!("CARGO_MANIFEST_DIR")).join("../descriptions/lafert-smartris");
    let parameters: Vec<String> = PARAMETERS.iter().map(|p| format!("\"{p}\"")).collect();
    let mut text = format!("format = 1\nread_only = true\n\n[mqtt]\nport = {port}\n");
    for (i, addr) in addrs.iter().enumerate() {
        text += &format!(
            "\n[[drive]]\nname = \"d{i}\"\ndescription = \"{}\"\nbus = {{ modbus_tcp = \"{addr}\" }}\n\
             interval_ms = {}\npublish_every_poll = true\nparameters = [{}]\n",
            lafert.display(),
            settings.period_ms,
            parameters.join(", ")
        );
    }
    let file = dir.join("gateway.toml");
    std::fs::write(&file, text).expect("the scratch folder is writable");
    file
}

/// Latencies of the values the subscriber got since the last sample.
type Window = Arc<Mutex<Histogram>>;

/// `mosquitto_sub` on every value topic; each line's payload time against now.
fn subscribe(port: u16, window: Window) -> Result<Process, String> {
    let mut child = Command::new("mosquitto_sub")
        .args([
            "-h",
            "127.0.0.1",
            "-p",
            &port.to_string(),
            "-v",
            "-t",
            "drivegen/+/+",
        ])
        .stdout(Stdio::piped())
        .spawn()
        .map_err(|e| format!("mosquitto_sub: {e}"))?;
    let out = child.stdout.take().ok_or("no stdout")?;
    std::thread::spawn(move || {
        for line in BufReader::new(out).lines().map_while(Result::ok) {
            let Some(latency) = latency(&line) else {
                continue;
            };
            window
                .lock()
                .unwrap_or_else(|e| e.into_inner())
                .record(latency);
        }
    });
    Ok(Process::new(child))
}

/// From a value's read time to now; `None` for a status line or a payload without a time.
fn latency(line: &str) -> Option<Duration> {
    let (_, payload) = line.split_once(' ')?;
    let json: serde_json::Value = serde_json::from_str(payload).ok()?;
    let read = humantime::parse_rfc3339(json.get("time")?.as_str()?).ok()?;
    Some(SystemTime::now().duration_since(read).unwrap_or_default())
}

fn ms(d: Option<Duration>) -> String {
    d.map_or_else(
        || "> 1000".into(),
        |d| format!("{:.1}", d.as_secs_f64() * 1e3),
    )
}

fn mib(bytes: u64) -> f64 {
    bytes as f64 / (1024.0 * 1024.0)
}

fn main() -> Result<(), String> {
    let settings = settings()?;
    let here = std::env::current_exe().map_err(|e| e.to_string())?;
    let sim = Simulator::start(&here.with_file_name("mbap-sim"), settings.drives)
        .map_err(|e| format!("mbap-sim: {e} (cargo build --release -p benchmarks --bins)"))?;
    let dir = std::env::temp_dir().join(format!("drivegen-gateway-load-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    let port = mosquitto::free_port();
    let _broker = mosquitto::start(&dir, port, "allow_anonymous true\n");
    let window: Window = Arc::default();
    let _subscriber = subscribe(port, window.clone())?;
    let file = gateway_file(&dir, port, &settings, &sim.addrs);
    let drivegen = here.with_file_name("drivegen");
    let mut gateway = Process::new(
        Command::new(&drivegen)
            .arg("gateway")
            .arg(&file)
            .stderr(Stdio::null())
            .spawn()
            .map_err(|e| {
                format!(
                    "{}: {e} (cargo build --release -p drivegen-cli)",
                    drivegen.display()
                )
            })?,
    );
    let pid = gateway.child_mut().id();
    println!(
        "| t (s) | messages/s | p50 ms | p99 ms | gateway CPU % of one core | resident MiB | load average |"
    );
    println!("| ---: | ---: | ---: | ---: | ---: | ---: | --- |");
    let begin = Instant::now();
    let (mut last, mut last_cpu) = (begin, other_process_cpu(pid));
    let mut overall = Histogram::default();
    let mut taken = Histogram::default();
    let mut resident = Vec::new();
    while begin.elapsed() < Duration::from_secs(settings.seconds) {
        std::thread::sleep(settings.sample);
        std::mem::swap(
            &mut taken,
            &mut *window.lock().unwrap_or_else(|e| e.into_inner()),
        );
        let (now, cpu) = (Instant::now(), other_process_cpu(pid));
        let span = (now - last).as_secs_f64();
        let rss = other_resident_bytes(pid);
        resident.push(rss);
        println!(
            "| {:.0} | {:.0} | {} | {} | {:.0} | {:.1} | {} |",
            (now - begin).as_secs_f64(),
            taken.total() as f64 / span,
            ms(taken.quantile(0.5)),
            ms(taken.quantile(0.99)),
            (cpu - last_cpu).as_secs_f64() / span * 100.0,
            mib(rss),
            load_average()
        );
        (last, last_cpu) = (now, cpu);
        overall.drain_into(&mut taken);
    }
    let elapsed = begin.elapsed().as_secs_f64();
    println!(
        "\n{} drives x {} parameters every {} ms ({:.0} messages/s offered), {:.0} s: {:.0} \
         messages/s received, p50 {} ms, p99 {} ms; gateway resident {:.1} MiB at the first \
         sample, {:.1} MiB at the last, {:.1} MiB at most.",
        settings.drives,
        PARAMETERS.len(),
        settings.period_ms,
        (settings.drives * PARAMETERS.len()) as f64 * 1000.0 / settings.period_ms as f64,
        elapsed,
        overall.total() as f64 / elapsed,
        ms(overall.quantile(0.5)),
        ms(overall.quantile(0.99)),
        mib(resident.first().copied().unwrap_or(0)),
        mib(resident.last().copied().unwrap_or(0)),
        mib(resident.iter().max().copied().unwrap_or(0)),
    );
    drop(gateway);
    let _ = std::fs::remove_dir_all(&dir);
    Ok(())
}
