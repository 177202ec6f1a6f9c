//! EMCY frames decode through the drive's error table (user guide 4.9, lines 2566-2568: the i2t
//! limitation is sent as EMCY 0x2351, the alarm as 0x2350).

use drivebus::canopen::emcy::{Emcy, ErrorRegister};
use drivebus::canopen::NodeId;
use drivebus::ErrorClass;
use lafert_smartris::types::ErrorCode;
use lafert_smartris::EmcyCodes;

fn emcy(code: u16) -> Emcy {
    Emcy {
        node: NodeId::new(1).unwrap(),
        code,
        register: ErrorRegister::empty(),
        manufacturer: [0; 5],
    }
}

#[test]
fn i2t_warning_and_alarm_decode_with_their_class() {
    let warning = ErrorCode::from_emcy(&Emcy::decode(&emcy(0x2351).encode()).unwrap());
    assert_eq!(warning, ErrorCode::LOAD_LEVEL_WARNING);
    assert_eq!(warning.class(), Some(ErrorClass::Warning));
    let alarm = ErrorCode::from_emcy(&emcy(0x2350));
    assert_eq!(alarm.class(), Some(ErrorClass::Fault));
    assert_eq!(alarm.led_code(), Some((5, 2)));
}

#[test]
fn the_emcy_table_gives_the_manuals_meaning() {
    assert_eq!(
        emcy(0x3220).meaning(&EmcyCodes),
        "Under Voltage alarm has occurred"
    );
    let unknown = ErrorCode::from_emcy(&emcy(0x1234));
    assert_eq!((unknown.is_known(), unknown.raw()), (false, 0x1234));
}

#[test]
fn the_emcy_codes_the_guide_sends_outside_table_2_are_known() {
    // Guide 4533-4534: after initialisation the drive sends 0000h and "the state of CAN (8170h)";
    // guide 2076-2078: a torque limit not correct at initialisation is EMCY 0x8B23.
    let can_state = ErrorCode::from_emcy(&Emcy::decode(&emcy(0x8170).encode()).unwrap());
    assert_eq!(can_state, ErrorCode::CAN_STATE);
    assert!(emcy(0x8170).meaning(&EmcyCodes).contains("state of CAN"));
    let torque_limit = ErrorCode::from_emcy(&emcy(0x8B23));
    assert_eq!(torque_limit, ErrorCode::TORQUE_LIMIT_NOT_CORRECT);
    // The guide gives them no fault/warning class: none is invented.
    assert_eq!(torque_limit.class(), None);
    assert_eq!(ErrorCode::from_emcy(&emcy(0x0000)), ErrorCode::NO_ERROR);
}
