//! The EMCY error table (section 9.8, lines 1506-1581) as data: 47 codes with their meanings,
//! the class where the manual names the level, and decoding of an emergency frame.

use drivebus::canopen::emcy::{describe, Emcy};
use drivebus::canopen::CanFrame;
use drivebus::ErrorClass;
use ezwheel_swd::types::EmcyErrorCode;
use ezwheel_swd::EmcyCodes;

#[test]
fn the_table_has_its_47_codes() {
    let printed: [u16; 47] = [
        0x0000, 0x1000, 0x2221, 0x2222, 0x3211, 0x3212, 0x3221, 0x3222, 0x4000, 0x4210, 0x4310,
        0x6000, 0x6020, 0x7100, 0x7121, 0x8001, 0x8002, 0x8003, 0x8004, 0x8005, 0x8006, 0x8007,
        0x8008, 0x8009, 0x800A, 0x800B, 0x800C, 0x800D, 0x800E, 0x8010, 0x8011, 0x8012, 0x8013,
        0x8014, 0x8015, 0x8016, 0x8017, 0x8018, 0x8050, 0x8120, 0x8140, 0x8201, 0x8202, 0x8203,
        0x8204, 0x8205, 0x8206,
    ];
    for code in printed {
        let known = EmcyErrorCode::try_from(code).unwrap_or_else(|e| panic!("{code:04X}: {e:?}"));
        assert!(known.meaning().is_some(), "{code:04X}");
    }
    assert!(EmcyErrorCode::try_from(0x800F).is_err(), "not in the table");
    // An unlisted code on the bus stays readable as an unknown value.
    let unknown =
        Emcy::decode(&CanFrame::new(0x90, &[0x0F, 0x80, 0x80, 0, 0, 0, 0, 0]).unwrap()).unwrap();
    assert_eq!(EmcyErrorCode::from_emcy(&unknown).meaning(), None);
    assert_eq!(EmcyErrorCode::from_emcy(&unknown).raw(), 0x800F);
}

fn code(raw: u16) -> EmcyErrorCode {
    EmcyErrorCode::try_from(raw).unwrap()
}

#[test]
fn safety_protocol_codes_carry_their_meaning() {
    assert_eq!(
        code(0x8201).meaning(),
        Some("SRDO protocol error - SCT not respected")
    );
    assert_eq!(
        code(0x8202).meaning(),
        Some("SRDO protocol error - SRVT not respected")
    );
    assert_eq!(
        code(0x8203).meaning(),
        Some("SRDO protocol error - data inconsistency")
    );
    assert_eq!(EmcyErrorCode::SRDO_SCT_NOT_RESPECTED.raw(), 0x8201);
}

#[test]
fn the_class_is_given_where_the_manual_names_the_level() {
    assert_eq!(
        EmcyErrorCode::DC_OVERVOLTAGE_ERROR.class(),
        Some(ErrorClass::Fault)
    );
    assert_eq!(
        EmcyErrorCode::DC_UNDERVOLTAGE_WARNING.class(),
        Some(ErrorClass::Warning)
    );
    assert_eq!(
        EmcyErrorCode::MOTOR_OVERCURRENT_WARNING.class(),
        Some(ErrorClass::Warning)
    );
    // "Fault on safety input STO_1" names no level: no class is invented.
    assert_eq!(EmcyErrorCode::STO_1_INPUT_FAULT.class(), None);
}

#[test]
fn an_emergency_frame_decodes_through_the_table() {
    // Node 10h: EMCY on 80h + 10h; code 8203h, error register 11h, no manufacturer bytes.
    let frame = CanFrame::new(0x90, &[0x03, 0x82, 0x11, 0, 0, 0, 0, 0]).unwrap();
    let emcy = Emcy::decode(&frame).unwrap();
    assert_eq!(
        EmcyErrorCode::from_emcy(&emcy),
        EmcyErrorCode::SRDO_DATA_INCONSISTENCY
    );
    assert_eq!(
        emcy.meaning(&EmcyCodes),
        "SRDO protocol error - data inconsistency"
    );
    assert_eq!(
        describe(0x8206, &EmcyCodes),
        "RPDO protocol error - ‘Event timer’ timeout"
    );
}
