//! Item 8 of the SWD issue: safety configuration is not writable through a plain setter. The SRDO
//! fixture describes SRDO1's information direction (1301h sub 1) as a read/write object; the
//! generated API still has no setter for it (a compile error naming `Writable<CanOpen>`), while
//! an ordinary read/write object of the same crate keeps its setter and the safety object its
//! getter.

mod support;

use std::path::Path;

use support::crate_build::{build_and_test, generated, no_std_lib};

const FIXTURE: &str = "tests/fixtures/srdo";

fn uses(body: &str) -> String {
    format!(
        "use drivebus::canopen::NodeId;\nuse drivebus::testing::MemoryBus;\nuse safety_no_setter::SwdSrdo;\n\n#[test]\nfn uses_the_api() {{\n    let mut drive = SwdSrdo::canopen(MemoryBus::new(), NodeId(0x10));\n{body}\n}}\n"
    )
}

#[test]
fn a_safety_object_has_a_getter_but_no_setter() {
    let lib = no_std_lib(&generated(Path::new(FIXTURE)));
    let allowed = uses(
        "    let _ = drive.srdo1_information_direction().read();\n    let _ = drive.safety_controlword_1().write(0u8);",
    );
    let built = build_and_test("safety_no_setter", &lib, &allowed);
    assert!(
        built.success,
        "reads and plain writes must build:\n{}",
        built.stderr
    );

    let refused = uses("    let _ = drive.srdo1_information_direction().write(0u8);");
    let built = build_and_test("safety_no_setter", &lib, &refused);
    assert!(!built.success, "a safety object must have no setter");
    assert!(
        built
            .stderr
            .contains("the parameter `Srdo1InformationDirection` cannot be written over CanOpen"),
        "{}",
        built.stderr
    );
    assert_eq!(
        built.stderr.matches("error[").count(),
        1,
        "{}",
        built.stderr
    );
}
