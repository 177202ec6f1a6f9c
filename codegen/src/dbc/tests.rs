use super::*;
use crate::test_support::{device, shipped};

fn lines_starting(text: &str, prefix: &str) -> Vec<String> {
    text.lines()
        .filter(|l| l.trim_start().starts_with(prefix))
        .map(str::to_owned)
        .collect()
}

#[test]
fn kinco_pdos_are_messages_with_typed_signals() {
    let dbc = export(&shipped("kinco-fd"), 3);
    assert!(dbc.skipped.is_empty(), "{:?}", dbc.skipped);
    let text = &dbc.text;
    assert!(text.contains("\nBU_: KincoFd\n"), "{text}");
    // TPDO 1 at 180h + 3, sent by the drive: position (i32) then statusword (u16), 6 bytes.
    assert!(text.contains("\nBO_ 387 tpdo1: 6 KincoFd\n"), "{text}");
    assert!(
        text.contains(
            " SG_ position_actual : 0|32@1- (1,0) [-2147483648|2147483647] \"inc\" Vector__XXX\n"
        ),
        "{text}"
    );
    assert!(text.contains(" SG_ statusword : 32|16@1+ (1,0) [0|65535] \"\" Vector__XXX\n"));
    // RPDO 1 at 200h + 3, received by the drive: the mode is an enumeration.
    assert!(text.contains("\nBO_ 515 rpdo1: 7 Vector__XXX\n"), "{text}");
    let tables = lines_starting(text, "VAL_ 515 modes_of_operation ");
    assert_eq!(tables.len(), 1, "{text}");
    assert!(
        tables[0].contains(" -3 \"immediate_velocity\""),
        "{}",
        tables[0]
    );
    assert!(tables[0].ends_with(" ;"));
    assert_eq!(lines_starting(text, "BO_ ").len(), 3);
}

const TWO_PDOS: &str = r#"
[[parameter]]
name = "speed"
doc = "A \"speed\", in tenths of a hertz."
type = "i16"
unit = "Hz"
scale = 0.1
range = [-500, 500]
canopen = { index = 0x2000, subindex = 0, access = "ro", pdo = "tx" }
source = { doc = "m", line = 2 }

[[parameter]]
name = "gain"
doc = "A float."
type = "f32"
canopen = { index = 0x2001, subindex = 0, access = "ro", pdo = "tx" }
source = { doc = "m", line = 3 }

[[pdo]]
name = "fast"
direction = "tx"
number = 5
enabled = false
entries = ["speed", "gain"]
source = { doc = "m", line = 4 }

[[pdo]]
name = "slow"
direction = "tx"
number = 2
enabled = false
entries = ["speed", "speed"]
source = { doc = "m", line = 5 }
"#;

#[test]
fn scale_range_floats_duplicates_and_a_pdo_without_identifier() {
    let dbc = export(&device(TWO_PDOS), 1);
    assert_eq!(dbc.skipped.len(), 1, "{:?}", dbc.skipped);
    assert!(
        dbc.skipped[0].starts_with("fast: no COB-ID"),
        "{:?}",
        dbc.skipped
    );
    let text = &dbc.text;
    // TPDO 2 of the predefined connection set: 280h + 1.
    assert!(text.contains("\nBO_ 641 slow: 4 Test\n"), "{text}");
    assert!(
        text.contains(" SG_ speed : 0|16@1- (0.1,0) [-50|50] \"Hz\" Vector__XXX\n"),
        "{text}"
    );
    assert!(text.contains(" SG_ speed_2 : 16|16@1- (0.1,0) [-50|50] \"Hz\" Vector__XXX\n"));
    assert!(text.contains("CM_ SG_ 641 speed \"A 'speed', in tenths of a hertz.\";"));
    assert!(
        text.contains("CM_ BO_ 641 \"TPDO2 (not valid by default"),
        "{text}"
    );
}

#[test]
fn a_float_signal_is_declared_a_float() {
    let body = TWO_PDOS.replace("number = 5", "number = 3");
    let text = export(&device(&body), 1).text;
    assert!(text.contains("\nBO_ 897 fast: 6 Test\n"), "{text}");
    assert!(text.contains("SIG_VALTYPE_ 897 gain : 1;"), "{text}");
    assert!(
        text.contains(" SG_ gain : 16|32@1- (1,0) [0|0] \"\" Vector__XXX\n"),
        "{text}"
    );
}

#[test]
fn text_is_what_dbc_can_hold() {
    assert_eq!(text::identifier("3 phase-motor"), "_3_phase_motor");
    assert_eq!(text::number(0.1), "0.1");
    assert_eq!(text::number(-5.0), "-5");
    assert_eq!(text::number(4_294_967_295.0), "4294967295");
}
