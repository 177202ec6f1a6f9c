//! LSS support (CiA 305) crosses the EDS both ways as CiA 306 has it: `[DeviceInfo]
//! LSS_Supported=1`. The SWD manual says the drive is an LSS slave; the others say nothing.

use std::path::Path;

fn exported(name: &str) -> String {
    let checked = drivegen::check(&Path::new("../descriptions").join(name));
    drivegen::eds::export(&checked.device.expect("a valid shipped description"))
}

#[test]
fn the_lss_slave_is_exported_and_imported_as_lss_supported() {
    let swd = exported("ezwheel-swd");
    assert!(swd.contains("\n[DeviceInfo]\n") && swd.contains("\nLSS_Supported=1\n"));
    assert!(!exported("lafert-smartris").contains("LSS_Supported"));
    let path = std::env::temp_dir().join(format!("drivegen-lss-{}.eds", std::process::id()));
    std::fs::write(&path, &swd).unwrap();
    let imported = drivegen::check(&path).device.expect("the export imports");
    std::fs::remove_file(&path).unwrap();
    let lss = imported.canopen.and_then(|c| c.lss);
    assert!(
        lss.is_some_and(|l| l.source.is_none()),
        "the EDS is the citation"
    );
}
