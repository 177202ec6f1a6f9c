//! Every shipped CANopen description exports an EDS whose `[MandatoryObjects]` lists the CiA 301
//! mandatory objects 1000h, 1001h and 1018h (CiA 306 §4.5.2), as CANopen masters expect.

use std::path::Path;

const CANOPEN_DESCRIPTIONS: &[&str] = &["ezwheel-swd", "kinco-fd", "lafert-smartris"];

fn section<'a>(eds: &'a str, name: &str) -> Vec<&'a str> {
    let header = format!("[{name}]");
    eds.lines()
        .skip_while(|l| *l != header)
        .skip(1)
        .take_while(|l| !l.starts_with('['))
        .filter(|l| !l.is_empty())
        .collect()
}

#[test]
fn exported_eds_lists_the_mandatory_objects() {
    for name in CANOPEN_DESCRIPTIONS {
        let path = Path::new("../descriptions").join(name);
        let checked = drivegen::check(&path);
        let device = checked
            .device
            .unwrap_or_else(|| panic!("{name} is valid:\n{}", checked.diagnostics.len()));
        let eds = drivegen::eds::export(&device);
        assert_eq!(
            section(&eds, "MandatoryObjects"),
            ["SupportedObjects=3", "1=0x1000", "2=0x1001", "3=0x1018"],
            "{name}"
        );
    }
}
