//! The EDS reader never panics: arbitrary bytes, and arbitrary arrangements of EDS-like lines
//! (sections, keys, values, `$NODEID` terms, hex, garbage), are read into diagnostics, whatever
//! device comes out can be exported and read again, and a valid one generates code.

use std::path::Path;

use drivegen::diagnostic::Files;
use proptest::prelude::*;

/// Reads `bytes` as an EDS, then exports and re-reads the device it describes.
fn read_everything(bytes: &[u8]) {
    let mut files = Files::default();
    let mut diagnostics = Vec::new();
    let model =
        drivegen::eds::read_bytes(Path::new("fuzz.eds"), bytes, &mut files, &mut diagnostics);
    for d in &diagnostics {
        let _ = d.render(&files);
    }
    let mut device = drivegen::eds::empty_device("Fuzz", &model);
    device.parameters =
        drivegen::eds::typed_parameters(model.entries, &model.cited, &mut diagnostics);
    let errors = drivegen::validate::validate(&device);
    if !errors
        .iter()
        .any(|d| d.severity == drivegen::Severity::Error)
    {
        drivegen::emit::rust::generate(&device, "fuzz");
    }
    let exported = drivegen::eds::export(&device);
    let mut again = Vec::new();
    let _ = drivegen::eds::read_bytes(
        Path::new("again.eds"),
        exported.as_bytes(),
        &mut files,
        &mut again,
    );
}

fn eds_line() -> impl Strategy<Value = String> {
    let section = prop_oneof![
        "[0-9A-F]{4}".prop_map(|i| format!("[{i}]")),
        ("[0-9A-F]{4}", "[0-9A-F]{1,3}").prop_map(|(i, s)| format!("[{i}sub{s}]")),
        "[0-9A-F]{4}".prop_map(|i| format!("[{i}Name]")),
        "[0-9A-F]{4}".prop_map(|i| format!("[{i}Value]")),
        Just("[DeviceInfo]".to_owned()),
        Just("[DummyUsage]".to_owned()),
        Just("[Comments]".to_owned()),
        Just("[DeviceComissioning]".to_owned()),
    ];
    let key = prop_oneof![
        Just("ParameterName"),
        Just("ObjectType"),
        Just("DataType"),
        Just("AccessType"),
        Just("PDOMapping"),
        Just("LowLimit"),
        Just("HighLimit"),
        Just("DefaultValue"),
        Just("ParameterValue"),
        Just("SubNumber"),
        Just("CompactSubObj"),
        Just("NrOfEntries"),
        Just("NodeID"),
        Just("Lines"),
        Just("1"),
    ];
    let value = prop_oneof![
        "0x[0-9A-Fa-f]{0,20}",
        "-?[0-9]{1,22}",
        "-0x[0-9A-F]{1,18}",
        Just("$NODEID+0x180".to_owned()),
        Just("0x180 + $NodeID".to_owned()),
        Just("$NODEID+$NODEID".to_owned()),
        Just("ro".to_owned()),
        Just("rww".to_owned()),
        "[ -~]{0,12}",
        "\\PC{0,8}",
    ];
    prop_oneof![
        section,
        (key, value).prop_map(|(k, v)| format!("{k}={v}")),
        "[ -~]{0,20}",
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn arbitrary_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..512)) {
        read_everything(&bytes);
    }

    #[test]
    fn arbitrary_eds_like_files_never_panic(lines in proptest::collection::vec(eds_line(), 0..60)) {
        read_everything(lines.join("\n").as_bytes());
    }
}

#[test]
fn bytes_that_once_looked_dangerous_are_read() {
    for bytes in [
        &b"[1000]\nCompactSubObj=254\nDataType=0x7\nAccessType=ro\nObjectType=0x8\n"[..],
        b"[1000]\nDataType=0x0015\nDefaultValue=-0x8000000000000000\nLowLimit=0xFFFFFFFFFFFFFFFFFFFF\n",
        b"[1000]\nDataType=0x1B\nHighLimit=18446744073709551615\n",
        b"\xEF\xBB\xBF\xFF\xFE[",
        b"[Comments]\nLines=4294967295\n",
    ] {
        read_everything(bytes);
    }
}
