//! The manual's worked values: the start-up statuswords (lines 2388-2396 and 4158-4163), the
//! store / restore signatures (lines 1942-1966), the vl dimension factor (line 2540), the SRDO 1
//! COB-IDs at the factory node (line 1741 and the quick start, lines 4119-4120), the safety command
//! codes of the default safety word mappings (lines 2933-2951, 3031-3039) and the default SRDO
//! signatures of 13FFh (lines 3587-3600).

mod support;

use drivebus::control::State;
use drivebus::units::Rpm;
use drivebus::ValueError;
use drivegen::ir::{Device, Number};
use support::simulated_swd::{start, DESCRIPTION};

fn description() -> Device {
    drivegen::check(std::path::Path::new(DESCRIPTION))
        .device
        .unwrap()
}

fn default(device: &Device, name: &str) -> i64 {
    match device.parameter(name).and_then(|p| p.default) {
        Some(Number::Int(value)) => value,
        other => panic!("{name}: {other:?}"),
    }
}

#[test]
fn the_start_up_statuswords_are_the_cia402_states() {
    // Lines 2390-2394: 0000h, 0040h, 0021h, 0023h, 0027h; line 4158: 0028h / 0008h fault;
    // line 4165: 0007h quick stop.
    assert_eq!(State::decode(0x0000), Some(State::NotReadyToSwitchOn));
    assert_eq!(State::decode(0x0040), Some(State::SwitchOnDisabled));
    assert_eq!(State::decode(0x0060), Some(State::SwitchOnDisabled));
    assert_eq!(State::decode(0x0021), Some(State::ReadyToSwitchOn));
    assert_eq!(State::decode(0x0023), Some(State::SwitchedOn));
    assert_eq!(State::decode(0x0027), Some(State::OperationEnabled));
    assert_eq!(State::decode(0x0028), Some(State::Fault));
    assert_eq!(State::decode(0x0008), Some(State::Fault));
    assert_eq!(State::decode(0x0007), Some(State::QuickStopActive));
}

#[test]
fn store_and_restore_signatures_spell_save_and_load() {
    let device = description();
    // "e v a s" MSB..LSB = 65 76 61 73h (line 1946); "d a o l" = 64 61 6F 6Ch (line 1966).
    assert_eq!(0x6576_6173u32.to_le_bytes(), *b"save");
    assert_eq!(0x6461_6F6Cu32.to_le_bytes(), *b"load");
    let command = |name: &str| {
        device
            .parameter(name)
            .and_then(|p| p.command.as_ref())
            .and_then(|c| c.value)
    };
    assert_eq!(command("store_all_parameters"), Some(0x6576_6173));
    assert_eq!(command("restore_all_default_parameters"), Some(0x6461_6F6C));
}

#[test]
fn the_dimension_factor_scales_every_vl_speed() {
    // Line 2540: speed [rpm] = numerator / denominator × speed [user unit].
    let (mut drive, _node) = start();
    drive.vl_dimension_factor_numerator().write(1).unwrap();
    drive.vl_dimension_factor_denominator().write(10).unwrap();
    // A user unit of 0.1 rpm: 29.8 rpm is 298 on the wire.
    drive.vl_target_velocity().write(Rpm(29.8)).unwrap();
    assert_eq!(drive.vl_target_velocity().read_raw().unwrap(), 298);
    // The limits scale too (line 2546): 1800 raw is 180 rpm now.
    assert_eq!(drive.vl_velocity_max_amount().read().unwrap(), Rpm(180.0));
    // A zero factor is refused before it is sent: the drive forbids it ("I32 excepted 0",
    // lines 2537-2538), the scale cannot divide by it. The description's range is 1..=i32::MAX
    // (ERRATA.md: a range cannot have a hole), so a negative factor is refused as well.
    for zero_or_negative in [0, -1] {
        for result in [
            drive
                .vl_dimension_factor_denominator()
                .write(zero_or_negative),
            drive
                .vl_dimension_factor_numerator()
                .write(zero_or_negative),
        ] {
            assert!(
                matches!(
                    result,
                    Err(drivebus::Error::Value(ValueError::OutOfRange { .. }))
                ),
                "{zero_or_negative}: {result:?}"
            );
        }
    }
    assert_eq!(drive.vl_dimension_factor_denominator().read().unwrap(), 10);
    assert_eq!(drive.vl_dimension_factor_numerator().read().unwrap(), 1);
    assert_eq!(drive.vl_target_velocity().read().unwrap(), Rpm(29.8));
}

#[test]
fn srdo1_cob_ids_at_the_factory_node() {
    let device = description();
    // "0000 00FFh + (2 x node-ID)" and "0000 0100h + (2 x node-ID)" at node 10h.
    assert_eq!(default(&device, "srdo1_cob_id_1"), 0xFF + 2 * 0x10);
    assert_eq!(default(&device, "srdo1_cob_id_2"), 0x100 + 2 * 0x10);
    assert_eq!(default(&device, "node_id"), 0x10);
}

#[test]
fn default_safety_word_mappings_hold_the_command_codes() {
    let device = description();
    // Code table, lines 2935-2937: STO 6640 0000h, RESTART_ACK 6630 0000h, ERROR_ACK 6632 0000h;
    // status codes 6644 0000h, 6631 0000h, 6633 0000h.
    assert_eq!(
        default(&device, "safety_controlword_1_sto_command"),
        0x6640_0000
    );
    assert_eq!(
        default(&device, "safety_controlword_1_restart_ack_command"),
        0x6630_0000
    );
    assert_eq!(
        default(&device, "safety_controlword_1_error_ack_command"),
        0x6632_0000
    );
    assert_eq!(
        default(&device, "safety_statusword_1_sto_status"),
        0x6644_0000
    );
    assert_eq!(
        default(&device, "safety_statusword_1_restart_ack_status"),
        0x6631_0000
    );
    assert_eq!(
        default(&device, "safety_statusword_1_error_ack_status"),
        0x6633_0000
    );
    // Safein: STO_1 and STO_2 fixed to STO (lines 3067-3068); 6643h defaults to SBC 3.
    assert_eq!(default(&device, "safein_command_sto_2"), 0x6640_0000);
    assert_eq!(default(&device, "sto_activate_sbc"), 0x6660_0300);
}

#[test]
fn default_srdo_signatures_are_the_printed_ones() {
    let device = description();
    for (name, printed) in [
        ("srdo1_signature", 0x70AB),
        ("srdo2_signature", 0x8C5F),
        ("srdo9_signature", 0x6C9B),
        ("srdo10_signature", 0x2274),
        ("srdo11_signature", 0x78AE),
        ("srdo12_signature", 0x4052),
        ("srdo13_signature", 0x9968),
        ("srdo14_signature", 0x1BF6),
        ("srdo15_signature", 0x3A94),
        ("srdo16_signature", 0x9941),
    ] {
        assert_eq!(default(&device, name), printed, "{name}");
    }
}
