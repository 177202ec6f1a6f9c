//! Kinco RS-232 telegram codec: what the blocking host does between its I/O calls for one read
//! (encode the upload telegram, find and decode the answer), drivebus against the hand-written
//! floor of `benchmarks/src/rs232.rs`, in the same run. Target: drivebus ≤ 1.2× floor.
//!
//! `cargo bench -p benchmarks --bench rs232` (about 15 s after the build) prints the
//! criterion medians and interleaved minima (the fastest of 40 rounds, each round timing both
//! back to back) with their ratio.

use std::hint::black_box;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use benchmarks::rs232 as floor;
use criterion::Criterion;
use drivebus::rs232::data::{Answer, Request};
use drivebus::rs232::exchange::Exchange;
use drivebus::rs232::{LoopMode, StationId};

const STATION: u8 = 1;
const INDEX: u16 = 0x607A;
const SUBINDEX: u8 = 0;
/// The answer to the upload of 607Ah: 43h, 50000 (the manual's target position, line 2332).
const ANSWER: [u8; 10] = [0x01, 0x43, 0x7A, 0x60, 0x00, 0x50, 0xC3, 0x00, 0x00, 0xCF];

type Op = fn(&[u8]) -> u32;

/// What `Rs232Client::exchange` does between `send` and the last `receive`, and the value
/// zero-extended as the floor returns it.
#[inline(never)]
fn drivebus(answer: &[u8]) -> u32 {
    let request = Request::upload(black_box(INDEX), black_box(SUBINDEX));
    let mut exchange = Exchange::new(
        StationId(black_box(STATION)),
        request,
        LoopMode::PointToPoint,
    );
    black_box(exchange.telegram());
    match exchange.receive(answer) {
        Ok(Some(Answer::Uploaded(_, value))) => value.to_u32(),
        other => panic!("not the answer: {other:?}"),
    }
}

#[inline(never)]
fn hand_written(answer: &[u8]) -> u32 {
    let (station, index, subindex) = (black_box(STATION), black_box(INDEX), black_box(SUBINDEX));
    let mut telegram = [0u8; 10];
    floor::encode_upload(station, index, subindex, &mut telegram);
    black_box(&telegram);
    floor::decode_upload(station, index, subindex, answer).unwrap()
}

const CODECS: [(&str, Op); 2] = [("drivebus", drivebus), ("floor", hand_written)];

fn codec(c: &mut Criterion) {
    let mut group = c.benchmark_group("codec_rs232");
    group
        .measurement_time(Duration::from_secs(2))
        .sample_size(60);
    for (name, op) in CODECS {
        assert_eq!(op(&ANSWER), 50_000, "{name} decodes the answer");
        group.bench_function(name, |b| b.iter(|| op(black_box(&ANSWER))));
    }
    group.finish();
}

/// The fastest of 40 rounds of each, timed back to back.
fn interleaved() -> [f64; 2] {
    const ROUNDS: usize = 40;
    const ITERS: u32 = 100_000;
    let mut best = [f64::MAX; 2];
    for _ in 0..ROUNDS {
        for (slot, (_, op)) in best.iter_mut().zip(CODECS) {
            let started = Instant::now();
            for _ in 0..ITERS {
                black_box(op(black_box(&ANSWER)));
            }
            *slot = slot.min(started.elapsed().as_nanos() as f64 / f64::from(ITERS));
        }
    }
    best
}

fn main() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../target/criterion-rs232");
    let mut c = Criterion::default()
        .warm_up_time(Duration::from_millis(300))
        .output_directory(&dir)
        .configure_from_args();
    codec(&mut c);
    c.final_summary();
    let [ours, floor] = interleaved();
    println!(
        "interleaved minima: drivebus {ours:.2} ns, floor {floor:.2} ns, drivebus / floor {:.2}×",
        ours / floor
    );
}
