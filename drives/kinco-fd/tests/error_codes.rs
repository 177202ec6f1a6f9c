//! Error_State (2601h) and Error_State2 (2602h) bits as data: each set bit gives its error code
//! (table 4, lines 1277-1315) and the code its reason and remedy (tables 7-1 and 7-2).

use drivebus::modbus::{Table, UnitId};
use drivebus::testing::MemoryBus;
use kinco_fd::types::{ErrorCode, ErrorState, ErrorState2};
use kinco_fd::KincoFd;

#[test]
fn set_bits_read_as_codes_with_their_remedies() {
    let mut memory = MemoryBus::new();
    // Bit 5 overvoltage, bit 9 following error (8.12, line 2123).
    memory.set_register(Table::Holding, 0x1F00, (1 << 5) | (1 << 9));
    let mut drive = KincoFd::modbus(memory, UnitId(1));
    let state = drive.error_state().read().unwrap();
    assert_eq!(state, ErrorState::OVERVOLTAGE | ErrorState::FOLLOWING_ERROR);
    let codes: Vec<ErrorCode> = state.codes().collect();
    assert_eq!(codes, [ErrorCode::OVERVOLTAGE, ErrorCode::FOLLOWING_ERROR]);
    assert_eq!(codes[0].raw(), 0x3210);
    assert!(codes[0].meaning().unwrap().contains("braking resistor"));
    assert!(codes[1].meaning().unwrap().contains("Max_Following_Error"));
}

#[test]
fn every_coded_bit_of_both_words_has_a_remedy() {
    let first = ErrorState::CODES.iter().map(|(_, code)| code);
    let second = ErrorState2::CODES.iter().map(|(_, code)| code);
    for code in first.chain(second) {
        assert!(code.meaning().is_some(), "{code:?}");
    }
    assert_eq!(
        ErrorState::CODES.len(),
        15,
        "bits 1-15 (bit 0 points to Error_State2)"
    );
    assert_eq!(ErrorState2::CODES.len(), 11);
    let extended = ErrorState2::MOTOR_CONFIGURATION;
    assert_eq!(extended.codes().next().map(|c| c.raw()), Some(0x6320));
}
