//! SRDO consumer and producer: the manual's SRDO1 frames, every refusal, and properties over
//! arbitrary frames (no panic; an inconsistent pair never yields data).
#![cfg(feature = "canopen")]

use std::time::Duration;

use drivebus::canopen::pdo::{MappedObject, PdoLayout};
use drivebus::canopen::srdo::mapping::{data_bits, normal_entries};
use drivebus::canopen::srdo::{
    is_complement, SrdoCobIds, SrdoConsumer, SrdoError, SrdoProducer, SrdoTiming,
};
use drivebus::canopen::CanFrame;
use proptest::prelude::*;

fn ms(n: u64) -> Duration {
    Duration::from_millis(n)
}

/// SRDO1 at the quick start's node 0x10: COB-IDs FFh + 2 × 10h and 100h + 2 × 10h, SCT 50 ms,
/// SRVT 20 ms, one byte (SWD manual lines 1738-1746, 4100, 4111).
fn srdo1() -> SrdoConsumer {
    let ids = SrdoCobIds::new(0x11F, 0x120).unwrap();
    SrdoConsumer::new(ids, SrdoTiming::from_millis(50, 20).unwrap(), 8).unwrap()
}

fn frame(id: u16, data: &[u8]) -> CanFrame {
    CanFrame::new(id, data).unwrap()
}

#[test]
fn quick_start_frames_release_the_safety_control_word() {
    let mut consumer = srdo1();
    // Line 4111: 11Fh FFh, then 120h 00h.
    assert_eq!(
        consumer.handle(&frame(0x11F, &[0xFF]), ms(0)),
        Some(Ok(None))
    );
    let value = consumer.handle(&frame(0x120, &[0x00]), ms(2)).unwrap();
    assert_eq!(value.unwrap().unwrap().as_bytes(), [0xFF]);
}

#[test]
fn other_frames_are_not_ours() {
    let mut consumer = srdo1();
    assert_eq!(consumer.handle(&frame(0x190, &[0xFF]), ms(0)), None);
}

#[test]
fn a_disagreeing_pair_yields_no_value() {
    let mut consumer = srdo1();
    consumer.handle(&frame(0x11F, &[0xFF]), ms(0));
    assert_eq!(
        consumer.handle(&frame(0x120, &[0x01]), ms(1)),
        Some(Err(SrdoError::Inconsistent))
    );
}

#[test]
fn a_late_inverted_frame_yields_no_value() {
    let mut consumer = srdo1();
    consumer.handle(&frame(0x11F, &[0xFF]), ms(0));
    assert_eq!(
        consumer.handle(&frame(0x120, &[0x00]), ms(21)),
        Some(Err(SrdoError::SrvtExpired {
            waited: ms(21),
            srvt: ms(20)
        }))
    );
}

#[test]
fn an_inverted_frame_at_exactly_srvt_is_in_time() {
    let mut consumer = srdo1();
    consumer.handle(&frame(0x11F, &[0x0F]), ms(0));
    assert!(matches!(
        consumer.handle(&frame(0x120, &[0xF0]), ms(20)),
        Some(Ok(Some(_)))
    ));
}

#[test]
fn lone_frames_yield_no_value() {
    let mut consumer = srdo1();
    assert_eq!(
        consumer.handle(&frame(0x120, &[0x00]), ms(0)),
        Some(Err(SrdoError::LoneInverted))
    );
    consumer.handle(&frame(0x11F, &[0xFF]), ms(1));
    assert_eq!(
        consumer.handle(&frame(0x11F, &[0xFF]), ms(2)),
        Some(Err(SrdoError::LoneNormal))
    );
}

#[test]
fn a_normal_frame_whose_inverted_never_comes_expires_on_poll() {
    let mut consumer = srdo1();
    consumer.handle(&frame(0x11F, &[0xFF]), ms(0));
    assert_eq!(consumer.next_deadline(), Some(ms(20)));
    assert_eq!(consumer.poll(ms(20)), Ok(()));
    assert!(matches!(
        consumer.poll(ms(21)),
        Err(SrdoError::SrvtExpired { .. })
    ));
    // Reported once; the late inverted frame is then alone.
    assert_eq!(consumer.poll(ms(22)), Ok(()));
    assert_eq!(
        consumer.handle(&frame(0x120, &[0x00]), ms(23)),
        Some(Err(SrdoError::LoneInverted))
    );
}

#[test]
fn wrong_lengths_and_remote_frames_are_refused() {
    let mut consumer = srdo1();
    assert_eq!(
        consumer.handle(&frame(0x11F, &[0xFF, 0x00]), ms(0)),
        Some(Err(SrdoError::WrongLength {
            cob_id: 0x11F,
            expected: 1,
            actual: 2
        }))
    );
    consumer.handle(&frame(0x11F, &[0xFF]), ms(1));
    assert_eq!(
        consumer.handle(&CanFrame::remote(0x120, 1).unwrap(), ms(2)),
        Some(Err(SrdoError::RemoteFrame { cob_id: 0x120 }))
    );
    // The refused frame dropped the waiting normal frame.
    assert_eq!(
        consumer.handle(&frame(0x120, &[0x00]), ms(3)),
        Some(Err(SrdoError::LoneInverted))
    );
}

#[test]
fn sct_expires_without_a_pair_and_rearms_at_the_next_pair() {
    let mut consumer = srdo1();
    consumer.start(ms(0));
    assert_eq!(consumer.poll(ms(50)), Ok(()));
    assert_eq!(
        consumer.poll(ms(51)),
        Err(SrdoError::SctExpired {
            since_last: ms(51),
            sct: ms(50)
        })
    );
    assert_eq!(consumer.poll(ms(200)), Ok(()));
    consumer.handle(&frame(0x11F, &[0xFF]), ms(200));
    assert!(matches!(
        consumer.handle(&frame(0x120, &[0x00]), ms(201)),
        Some(Ok(Some(_)))
    ));
    assert!(matches!(
        consumer.poll(ms(251)),
        Err(SrdoError::SctExpired { .. })
    ));
}

#[test]
fn a_normal_frame_after_sct_reports_the_expiry_and_still_pairs() {
    let mut consumer = srdo1();
    consumer.handle(&frame(0x11F, &[0xFF]), ms(0));
    consumer.handle(&frame(0x120, &[0x00]), ms(1));
    assert!(matches!(
        consumer.handle(&frame(0x11F, &[0xFE]), ms(60)),
        Some(Err(SrdoError::SctExpired { .. }))
    ));
    assert!(matches!(
        consumer.handle(&frame(0x120, &[0x01]), ms(61)),
        Some(Ok(Some(_)))
    ));
}

#[test]
fn bad_timings_and_widths_are_refused() {
    assert!(SrdoTiming::from_millis(20, 20).is_err());
    assert!(SrdoTiming::from_millis(0, 0).is_err());
    assert!(SrdoCobIds::new(0x11F, 0x11F).is_err());
    assert!(SrdoCobIds::new(0x800, 0x120).is_err());
    assert!(SrdoCobIds::from_objects(0x8000_011F, 0x120).is_err());
    let ids = SrdoCobIds::new(0x11F, 0x120).unwrap();
    let timing = SrdoTiming::from_millis(50, 20).unwrap();
    assert!(SrdoConsumer::new(ids, timing, 0).is_err());
    assert!(SrdoConsumer::new(ids, timing, 65).is_err());
    assert!(SrdoProducer::new(ids, timing.sct(), 65).is_err());
}

/// SRDO2's default mapping, 16 entries (SWD manual lines 1767-1782): eight one-byte safety
/// status words at the odd sub-indices, their inverted copies at the even ones.
const SRDO2: [MappedObject; 16] = {
    let mut entries = [MappedObject::new(0, 0, 8); 16];
    let mut i = 0;
    while i < 8 {
        entries[2 * i] = MappedObject::new(0x6621, i as u8 + 1, 8);
        entries[2 * i + 1] = MappedObject::new(0x6623, i as u8 + 1, 8);
        i += 1;
    }
    entries
};

#[test]
fn srdo2_carries_sixteen_entries_and_128_bits() {
    let layout = PdoLayout::new(normal_entries::<8>(&SRDO2));
    let ids = SrdoCobIds::new(0x103, 0x104).unwrap();
    let timing = SrdoTiming::from_millis(25, 20).unwrap();
    let mut producer = SrdoProducer::new(ids, timing.sct(), data_bits(&SRDO2)).unwrap();
    let mut consumer = SrdoConsumer::new(ids, timing, data_bits(&SRDO2)).unwrap();
    let mut payload = [0u8; 8];
    for word in 0..8 {
        layout.set(&mut payload, word, (word as u8) * 17).unwrap();
    }
    let [normal, inverted] = producer.poll(ms(0), &payload).unwrap().unwrap();
    assert_eq!(producer.poll(ms(24), &payload), Ok(None));
    assert!(producer.poll(ms(25), &payload).unwrap().is_some());
    assert_eq!((normal.dlc(), inverted.dlc()), (8, 8));
    consumer.handle(&normal, ms(0));
    let value = consumer.handle(&inverted, ms(1)).unwrap().unwrap().unwrap();
    assert_eq!(layout.get::<u8>(value.as_bytes(), 7), Ok(7 * 17));
}

#[test]
fn the_producer_refuses_a_payload_of_the_wrong_length() {
    let ids = SrdoCobIds::new(0x11F, 0x120).unwrap();
    let producer = SrdoProducer::new(ids, ms(50), 8).unwrap();
    assert!(matches!(
        producer.pair(&[1, 2]),
        Err(SrdoError::WrongLength { .. })
    ));
}

fn any_frame() -> impl Strategy<Value = CanFrame> {
    (
        prop_oneof![Just(0x11Fu16), Just(0x120u16), 0u16..=0x7FF],
        proptest::collection::vec(any::<u8>(), 0..=8),
        any::<bool>(),
    )
        .prop_map(|(id, data, remote)| {
            if remote {
                CanFrame::remote(id, data.len() as u8).unwrap()
            } else {
                CanFrame::new(id, &data).unwrap()
            }
        })
}

/// One step of a random exchange: a random frame, a well-formed normal frame, or the complement
/// of the last normal frame (so that valid pairs occur often).
#[derive(Debug, Clone)]
enum Step {
    Random(CanFrame),
    Normal(u8),
    Complement,
}

fn any_step() -> impl Strategy<Value = Step> {
    prop_oneof![
        any_frame().prop_map(Step::Random),
        any::<u8>().prop_map(Step::Normal),
        Just(Step::Complement),
    ]
}

proptest! {
    /// Any frame sequence at any times: no panic, and every released value is the normal frame
    /// of a pair whose inverted frame, received at most SRVT later, was its complement.
    #[test]
    fn released_values_always_come_from_consistent_timely_pairs(
        steps in proptest::collection::vec((any_step(), 0u64..30), 0..64)
    ) {
        let mut consumer = srdo1();
        let mut now = ms(0);
        let mut last_normal: Option<(CanFrame, Duration)> = None;
        for (step, advance) in steps {
            now += ms(advance);
            let _ = consumer.poll(now);
            let frame = match step {
                Step::Random(frame) => frame,
                Step::Normal(byte) => frame(0x11F, &[byte]),
                Step::Complement => {
                    let byte = last_normal.map_or(0, |(normal, _)| normal.padded()[0]);
                    frame(0x120, &[!byte])
                }
            };
            let result = consumer.handle(&frame, now);
            if let Some(Ok(Some(value))) = result {
                let (normal, at) = last_normal.expect("a value without a normal frame");
                prop_assert_eq!(frame.id(), 0x120);
                prop_assert!(now - at <= ms(20));
                prop_assert_eq!(value.as_bytes(), normal.data());
                prop_assert!(is_complement(normal.data(), frame.data(), 8));
            }
            if frame.id() == 0x11F && !frame.is_remote() {
                last_normal = Some((frame, now));
            }
        }
    }

    /// A pair whose inverted data is anything but the complement never yields data.
    #[test]
    fn an_inconsistent_pair_never_yields_data(normal in any::<[u8; 8]>(), flip in 1u64..) {
        let ids = SrdoCobIds::new(0x103, 0x104).unwrap();
        let timing = SrdoTiming::from_millis(25, 20).unwrap();
        let producer = SrdoProducer::new(ids, timing.sct(), 64).unwrap();
        let mut consumer = SrdoConsumer::new(ids, timing, 64).unwrap();
        let [first, inverted] = producer.pair(&normal).unwrap();
        let corrupted = (u64::from_le_bytes(inverted.padded()) ^ flip).to_le_bytes();
        consumer.handle(&first, ms(0));
        prop_assert_eq!(
            consumer.handle(&frame(0x104, &corrupted), ms(1)),
            Some(Err(SrdoError::Inconsistent))
        );
    }

    /// What the producer sends, the consumer releases unchanged.
    #[test]
    fn producer_pairs_round_trip(normal in any::<[u8; 8]>(), bits in 1u32..=64) {
        let ids = SrdoCobIds::new(0x103, 0x104).unwrap();
        let timing = SrdoTiming::from_millis(25, 20).unwrap();
        let len = bits.div_ceil(8) as usize;
        let producer = SrdoProducer::new(ids, timing.sct(), bits).unwrap();
        let mut consumer = SrdoConsumer::new(ids, timing, bits).unwrap();
        let [first, second] = producer.pair(&normal[..len]).unwrap();
        consumer.handle(&first, ms(0));
        let value = consumer.handle(&second, ms(3)).unwrap().unwrap().unwrap();
        prop_assert_eq!(value.as_bytes(), &normal[..len]);
    }
}
