//! CANopen benchmarks: SDO expedited encode/decode, and decoding a 1,000,000-frame candump log
//! into typed values, compared with python-can + python-canopen on the same log; SRDO pair check
//! and safety signature (`canopen/srdo.rs`).
//!
//! `cargo bench -p drivebus --features canopen --bench canopen`
#![allow(missing_docs)] // `criterion_group!` defines an undocumented public function.

use std::hint::black_box;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

use criterion::{criterion_group, Criterion, Throughput};
use drivebus::canopen::can::candump::parse_line;
use drivebus::canopen::emcy::Emcy;
use drivebus::canopen::message::Message;
use drivebus::canopen::pdo::{MappedObject, PdoLayout};
use drivebus::canopen::sdo::{Progress, SdoClient, Transfer};
use drivebus::canopen::{CanFrame, NodeId};

#[path = "canopen/srdo.rs"]
mod srdo;

const FRAMES: usize = 1_000_000;
/// Frames the python decoder reads from the start of the same log; it runs ~100 times slower.
const PYTHON_FRAMES: usize = 200_000;

/// TPDO1 of node 5 as the python side maps it: u16 (0x2002), i32 (0x2004), u8 (0x2001).
const TPDO1: PdoLayout<3> = PdoLayout::new([
    MappedObject::new(0x2002, 0, 16),
    MappedObject::new(0x2004, 0, 32),
    MappedObject::new(0x2001, 0, 8),
]);

fn sdo_expedited(c: &mut Criterion) {
    let client = SdoClient::new(NodeId(5), Duration::from_millis(100));
    let response = CanFrame::new(0x585, &[0x43, 0x64, 0x60, 0x00, 0x10, 0x27, 0x00, 0x00]).unwrap();
    let mut group = c.benchmark_group("sdo");
    group.throughput(Throughput::Elements(1));
    group.bench_function("expedited upload: encode request + decode response", |b| {
        b.iter(|| {
            let mut buf = [0u8; 4];
            let mut transfer = client.upload(black_box(0x6064), 0, &mut buf, Duration::ZERO);
            let request = transfer.poll_transmit();
            let done = transfer.handle(black_box(&response), Duration::ZERO);
            black_box((request, done, buf))
        })
    });
    group.bench_function(
        "expedited download: encode request + decode response",
        |b| {
            let ack = CanFrame::new(0x585, &[0x60, 0x40, 0x60, 0x00, 0, 0, 0, 0]).unwrap();
            b.iter(|| {
                let mut transfer =
                    client.download(black_box(0x6040), 0, &[0x0F, 0x00], Duration::ZERO);
                let request = transfer.poll_transmit();
                let done = transfer.handle(black_box(&ack), Duration::ZERO);
                assert_eq!(done, Progress::Done(2));
                black_box(request)
            })
        },
    );
    group.finish();
}

/// A log of SDO responses, TPDOs, heartbeats and EMCYs, in candump log format.
fn generate_log(path: &Path) {
    let mut out = std::io::BufWriter::new(std::fs::File::create(path).expect("create log"));
    for i in 0..FRAMES {
        let (id, data): (u16, Vec<u8>) = match i % 8 {
            0..=3 => {
                let mut payload = [0u8; 8];
                TPDO1.set(&mut payload, 0, (i as u16) | 0x0237).unwrap();
                TPDO1.set(&mut payload, 1, i as i32 - 500_000).unwrap();
                TPDO1.set(&mut payload, 2, (i % 7) as u8).unwrap();
                (0x185, payload[..TPDO1.len()].to_vec())
            }
            4 | 5 => {
                let [a, b, c, d] = (i as u32).to_le_bytes();
                (0x585, vec![0x43, 0x03, 0x20, 0x00, a, b, c, d])
            }
            6 => (0x705, vec![0x05]),
            _ => (0x085, vec![0x10, 0x23, 0x03, 1, 2, 3, 4, 5]),
        };
        let hex: String = data.iter().map(|b| format!("{b:02X}")).collect();
        writeln!(out, "(1700000000.{:06}) can0 {id:03X}#{hex}", i % 1_000_000).unwrap();
    }
}

/// Decodes every line into typed values; returns a checksum so nothing is optimised away.
fn decode_log(log: &[u8], limit: usize) -> (usize, i64) {
    let mut frames = 0;
    let mut checksum = 0i64;
    for line in log.split(|&b| b == b'\n').take(limit) {
        let Ok(Some(record)) = parse_line(line) else {
            continue;
        };
        frames += 1;
        checksum += match Message::classify(&record.frame) {
            Message::Pdo { frame, .. } => {
                let data = frame.data();
                let status: u16 = TPDO1.get(data, 0).unwrap_or(0);
                let position: i32 = TPDO1.get(data, 1).unwrap_or(0);
                let mode: u8 = TPDO1.get(data, 2).unwrap_or(0);
                i64::from(status) + i64::from(position) + i64::from(mode)
            }
            message @ Message::SdoResponse { .. } => message
                .expedited_value()
                .map_or(0, |v| i64::from(v.as_u32())),
            Message::Heartbeat { state, .. } => i64::from(state.code()),
            Message::Emcy(Emcy { code, .. }) => i64::from(code),
            _ => 0,
        };
    }
    (frames, checksum)
}

fn log_path() -> PathBuf {
    PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("canopen-bench.log")
}

fn candump_decode(c: &mut Criterion) {
    let path = log_path();
    generate_log(&path);
    let log = std::fs::read(&path).unwrap();
    let mut group = c.benchmark_group("candump");
    group.throughput(Throughput::Elements(FRAMES as u64));
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(3));
    group.bench_function("decode 1M-frame log into typed values", |b| {
        b.iter(|| black_box(decode_log(black_box(&log), FRAMES)))
    });
    group.finish();
}

/// Times the Rust decoder (best of 3) and the python decoder on the same log; prints both.
fn compare_with_python() {
    let path = log_path();
    let log = std::fs::read(&path).unwrap();
    let rust = (0..3)
        .map(|_| {
            let start = Instant::now();
            black_box(decode_log(&log, FRAMES));
            FRAMES as f64 / start.elapsed().as_secs_f64()
        })
        .fold(0.0, f64::max);
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..");
    let python = std::env::var_os("DRIVEGEN_PYTHON")
        .map(PathBuf::from)
        .unwrap_or_else(|| {
            let venv = root.join(".venv/bin/python");
            if venv.exists() {
                venv
            } else {
                PathBuf::from("python3")
            }
        });
    let output = Command::new(&python)
        .arg(root.join("drivebus/benches/canopen_decode.py"))
        .arg(&path)
        .arg(root.join("tests/peers/canopen_peer.eds"))
        .arg(PYTHON_FRAMES.to_string())
        .output();
    println!(
        "\ncandump decode, Rust: {:.2} M frames/s ({FRAMES} frames, best of 3)",
        rust / 1e6
    );
    match output {
        Ok(out) if out.status.success() => {
            let text = String::from_utf8_lossy(&out.stdout);
            let field = |name: &str| {
                text.split(&format!("\"{name}\": "))
                    .nth(1)
                    .and_then(|rest| rest.split([',', '}']).next())
                    .map(|n| n.trim().to_string())
            };
            let rate = field("frames_per_second").and_then(|n| n.parse::<f64>().ok());
            // Both sides sum the same decoded values: equal checksums mean equal decoding.
            let (_, ours) = decode_log(&log, PYTHON_FRAMES);
            let theirs = field("checksum").and_then(|n| n.parse::<i64>().ok());
            println!(
                "decoded values agree with python-canopen: {}",
                theirs == Some(ours)
            );
            match rate {
                Some(rate) => println!(
                    "candump decode, python-can + canopen: {:.1} k frames/s ({PYTHON_FRAMES} frames of the same log)\nratio Rust / python: {:.0}x",
                    rate / 1e3,
                    rust / rate
                ),
                None => println!("python decoder printed no rate: {text}"),
            }
        }
        Ok(out) => println!(
            "python decoder failed: {}",
            String::from_utf8_lossy(&out.stderr)
        ),
        Err(e) => println!("python decoder not run ({e}); run tests/peers/setup-canopen.sh"),
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().warm_up_time(Duration::from_millis(500)).measurement_time(Duration::from_secs(2));
    targets = sdo_expedited, candump_decode, srdo::srdo
}

fn main() {
    benches();
    Criterion::default().configure_from_args().final_summary();
    compare_with_python();
}
