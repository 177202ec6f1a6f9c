//! The generated SRDO structs of the SWD's default SRDOs (lines 1715-1934) sign their default
//! configurations to the signatures 13FFh prints (lines 3588-3600), and SRDO 1 with reception
//! disabled signs to the quick start's BABDh (line 4111); the SRDO 9 and 16 errata are the only
//! readings that reproduce theirs.

use drivebus::canopen::pdo::MappedObject;
use drivebus::canopen::srdo::{signature, SrdoCommunication, SrdoConfig, SrdoDirection};
use drivebus::canopen::NodeId;
use drivegen::ir::{Device, Number};
use ezwheel_swd::srdo::{
    SafeActualValues, SafeInputs, SafetyControl1, SafetyControl2, SafetyControl3, SafetyControl4,
    SafetyControl5, SafetyControl6, SafetyControl78, SafetyStatus,
};

/// The factory node-ID (line 4100).
const NODE: NodeId = NodeId(0x10);

/// The description's default of `name`, as an integer of the width `T`.
fn printed<T: TryFrom<i64>>(name: &str) -> T {
    let device: Device = drivegen::check(std::path::Path::new("../../descriptions/ezwheel-swd"))
        .device
        .expect("the SWD description is valid");
    match device.parameter(name).and_then(|p| p.default) {
        Some(Number::Int(value)) => T::try_from(value).unwrap_or_else(|_| panic!("{name}: width")),
        other => panic!("{name}: {other:?}"),
    }
}

#[test]
fn every_declared_srdo_signs_to_the_printed_default() {
    let signed = [
        (
            signature(&SafetyControl1::config(NODE)),
            printed::<u16>("srdo1_signature"),
        ),
        (
            signature(&SafetyStatus::config(NODE)),
            printed::<u16>("srdo2_signature"),
        ),
        (
            signature(&SafetyControl2::config(NODE)),
            printed::<u16>("srdo9_signature"),
        ),
        (
            signature(&SafeActualValues::config(NODE)),
            printed::<u16>("srdo10_signature"),
        ),
        (
            signature(&SafetyControl3::config(NODE)),
            printed::<u16>("srdo11_signature"),
        ),
        (
            signature(&SafetyControl4::config(NODE)),
            printed::<u16>("srdo12_signature"),
        ),
        (
            signature(&SafetyControl5::config(NODE)),
            printed::<u16>("srdo13_signature"),
        ),
        (
            signature(&SafetyControl6::config(NODE)),
            printed::<u16>("srdo14_signature"),
        ),
        (
            signature(&SafetyControl78::config(NODE)),
            printed::<u16>("srdo15_signature"),
        ),
        (
            signature(&SafeInputs::config(NODE)),
            printed::<u16>("srdo16_signature"),
        ),
    ];
    for (number, (computed, printed)) in signed.into_iter().enumerate() {
        assert_eq!(computed, Ok(printed), "SRDO #{number} of the list");
    }
}

#[test]
fn the_printed_signatures_are_the_manuals() {
    // Lines 3588, 3593, 3600: the description's defaults are the printed values.
    assert_eq!(printed::<u16>("srdo1_signature"), 0x70AB);
    assert_eq!(printed::<u16>("srdo9_signature"), 0x6C9B);
    assert_eq!(printed::<u16>("srdo16_signature"), 0x9941);
}

#[test]
fn srdo1_with_reception_disabled_signs_to_the_quick_starts_babd() {
    let mut config = SafetyControl1::config(NODE);
    config.communication.direction = SrdoDirection::Invalid;
    assert_eq!(signature(&config), Ok(0xBABD));
}

#[test]
fn srdo9_signs_only_with_the_decided_cob_ids_and_entry() {
    let decided = SafetyControl2::config(NODE);
    let printed_cob_ids = SrdoConfig {
        communication: SrdoCommunication {
            cob_id_normal: 0x11F,
            cob_id_inverted: 0x120,
            ..decided.communication
        },
        ..decided
    };
    assert_ne!(signature(&printed_cob_ids), Ok(0x6C9B));
    let printed_entry = [
        MappedObject::new(0x6620, 2, 8),
        MappedObject::new(0x6622, 1, 8),
    ];
    let with_printed_entry = SrdoConfig {
        mapping: &printed_entry,
        ..decided
    };
    assert_ne!(signature(&with_printed_entry), Ok(0x6C9B));
}

#[test]
fn srdo16_signs_only_with_the_decided_sct_and_entry_width() {
    let decided = SafeInputs::config(NODE);
    assert_eq!(
        decided.mapping,
        [
            MappedObject::new(0x2620, 2, 8),
            MappedObject::new(0x2622, 2, 8),
        ]
    );
    assert_eq!(printed::<u16>("srdo16_sct"), 50);
    assert_eq!(signature(&decided), Ok(0x9941));
    let printed_sct = SrdoConfig {
        communication: SrdoCommunication {
            sct_ms: 25, // line 1926
            ..decided.communication
        },
        ..decided
    };
    assert_ne!(signature(&printed_sct), Ok(0x9941));
    // 2620h sub 2 as the U32 its table at line 3068 prints.
    let as_u32 = [
        MappedObject::new(0x2620, 2, 32),
        MappedObject::new(0x2622, 2, 32),
    ];
    let with_u32_entries = SrdoConfig {
        mapping: &as_u32,
        ..decided
    };
    assert_ne!(signature(&with_u32_entries), Ok(0x9941));
}

#[test]
fn srdo16_carries_the_safein_controlword_in_one_byte() {
    let inputs = SafeInputs {
        safein_controlword: 0b0000_0011,
    };
    let payload = inputs.encode().expect("any u8 fits");
    assert_eq!(payload.as_bytes(), [0x03]);
    assert_eq!(SafeInputs::decode(payload.as_bytes()), Ok(inputs));
    assert_eq!(SafeInputs::NUMBER, 16);
}
