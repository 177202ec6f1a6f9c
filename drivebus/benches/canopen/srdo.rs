//! SRDO benchmarks: the consumer's pair check (normal + inverted frame in, value out) and the
//! safety signature, on the SWD's SRDO1 (1 byte) and SRDO2 (8 bytes, 16 mapping entries).

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, Throughput};
use drivebus::canopen::pdo::MappedObject;
use drivebus::canopen::srdo::{
    signature, SrdoCobIds, SrdoCommunication, SrdoConfig, SrdoConsumer, SrdoDirection,
    SrdoProducer, SrdoTiming,
};

/// SRDO2's default mapping (SWD manual lines 1767-1782).
fn srdo2_mapping() -> Vec<MappedObject> {
    (1..=8u8)
        .flat_map(|i| {
            [
                MappedObject::new(0x6621, i, 8),
                MappedObject::new(0x6623, i, 8),
            ]
        })
        .collect()
}

fn pair_check(c: &mut Criterion, name: &str, ids: (u16, u16), payload: &[u8]) {
    let ids = SrdoCobIds::new(ids.0, ids.1).unwrap();
    let timing = SrdoTiming::from_millis(25, 20).unwrap();
    let bits = payload.len() as u32 * 8;
    let [normal, inverted] = SrdoProducer::new(ids, timing.sct(), bits)
        .unwrap()
        .pair(payload)
        .unwrap();
    let mut consumer = SrdoConsumer::new(ids, timing, bits).unwrap();
    let mut now = Duration::ZERO;
    let mut group = c.benchmark_group("srdo");
    group.throughput(Throughput::Elements(1));
    group.bench_function(name, |b| {
        b.iter(|| {
            now += Duration::from_millis(10);
            let first = consumer.handle(black_box(&normal), now);
            let value = consumer.handle(black_box(&inverted), now + Duration::from_micros(200));
            assert!(matches!(value, Some(Ok(Some(_)))));
            black_box((first, value))
        })
    });
    group.finish();
}

fn signing(c: &mut Criterion, name: &str, config: SrdoConfig<'_>) {
    let mut group = c.benchmark_group("srdo");
    group.bench_function(name, |b| b.iter(|| signature(black_box(&config)).unwrap()));
    group.finish();
}

/// The SRDO benchmarks.
pub fn srdo(c: &mut Criterion) {
    pair_check(
        c,
        "pair check: SRDO1, 1-byte frames",
        (0x11F, 0x120),
        &[0xFF],
    );
    pair_check(
        c,
        "pair check: SRDO2, 8-byte frames",
        (0x103, 0x104),
        &[1, 2, 4, 8, 16, 32, 64, 128],
    );
    let srdo1 = [
        MappedObject::from_entry(0x6620_0108),
        MappedObject::from_entry(0x6622_0108),
    ];
    let communication = |direction, sct_ms, cob_ids: (u32, u32)| SrdoCommunication {
        direction,
        sct_ms,
        srvt_ms: 20,
        transmission_type: 0xFE,
        cob_id_normal: cob_ids.0,
        cob_id_inverted: cob_ids.1,
    };
    signing(
        c,
        "signature: SRDO1 (2 entries, 23 bytes)",
        SrdoConfig {
            number: 1,
            communication: communication(SrdoDirection::Receive, 50, (0x11F, 0x120)),
            mapping: &srdo1,
        },
    );
    let srdo2 = srdo2_mapping();
    signing(
        c,
        "signature: SRDO2 (16 entries, 93 bytes)",
        SrdoConfig {
            number: 2,
            communication: communication(SrdoDirection::Transmit, 25, (0x103, 0x104)),
            mapping: &srdo2,
        },
    );
}
