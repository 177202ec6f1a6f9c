//! An EDS plus a TOML overlay: the overlay's entries refine the EDS objects they address, the rest
//! of the EDS is kept as written, and `import_overlay` writes an overlay that checks as is.

mod support;

use std::path::Path;

use drivegen::ir::{Access, Number, Pdo};
use support::{device, Scratch};

#[test]
fn overlay_entries_refine_their_eds_objects() {
    let d = device(Path::new("tests/fixtures/overlay"));
    let controlword = d.parameter("controlword").unwrap();
    assert_eq!(controlword.flags.as_deref(), Some("controlword"));
    assert_eq!(controlword.data_type.name(), "u16", "type from the EDS");
    assert_eq!(
        controlword.canopen[0].pdo,
        Pdo::Rx,
        "rww + PDOMapping from the EDS"
    );
    let speed = d.parameter("speed_limit").unwrap();
    assert_eq!(speed.data_type.name(), "u16", "type from the overlay");
    assert_eq!(speed.unit.as_deref(), Some("rpm"));
    assert_eq!(speed.default, Some(Number::Int(10)), "default from the EDS");
    assert_eq!(speed.source.as_ref().unwrap().doc(), "manual");
    let vendor_id = d.parameter("vendor_id").unwrap();
    assert_eq!(
        vendor_id.record.as_deref(),
        Some("identity"),
        "record renamed by the overlay"
    );
    assert_eq!(
        vendor_id.source.as_ref().unwrap().doc(),
        "eds",
        "citation from the EDS"
    );
    assert_eq!(vendor_id.canopen[0].access, Access::READ);
}

#[test]
fn objects_the_overlay_does_not_mention_keep_their_eds_names() {
    let d = device(Path::new("tests/fixtures/overlay"));
    let torque = d.parameter("vendor_torque").unwrap();
    assert_eq!(torque.data_type.name(), "i16");
    assert_eq!(torque.canopen[0].pdo, Pdo::Tx);
    let cob_id = d.parameter("cob_id_used_by_tpdo").unwrap();
    assert_eq!(
        (cob_id.default, cob_id.default_plus_node_id),
        (Some(Number::Int(0x180)), true)
    );
    assert_eq!(
        d.parameter("identity_object_highest_sub_index_supported")
            .and_then(|p| p.record.as_deref()),
        Some("identity")
    );
    assert_eq!(d.records.len(), 2);
}

#[test]
fn node_relative_defaults_are_generated_as_a_function_of_the_node_id() {
    let d = device(Path::new("tests/fixtures/overlay"));
    let code = drivegen::emit::rust::generate(&d, "overlay");
    assert!(code.contains("node id + 384"), "{code}");
    assert!(!code.contains("| 389"), "never baked in for one node");
}

/// Copies an EDS into a scratch directory, imports it, and checks the overlay beside it.
fn import_and_check(eds: &Path, scratch: &Scratch) -> drivegen::Checked {
    let copy = scratch.0.join(eds.file_name().unwrap());
    std::fs::copy(eds, &copy).unwrap();
    let path = scratch.0.join(format!(
        "{}.toml",
        eds.file_stem().unwrap().to_string_lossy()
    ));
    let imported = drivegen::eds::import_overlay(&copy, &path).unwrap_or_else(|e| panic!("{e}"));
    std::fs::write(&path, &imported.overlay).unwrap();
    let checked = drivegen::check(&path);
    assert_eq!(
        checked.render(),
        imported.checked.render(),
        "the import checks the overlay as it is saved"
    );
    checked
}

#[test]
fn imported_overlays_check_as_written_and_keep_every_object() {
    let scratch = Scratch::new("eds-import");
    let mut imported = 0;
    for entry in std::fs::read_dir("tests/eds").unwrap() {
        let eds = entry.unwrap().path();
        if !drivegen::eds::is_eds_path(&eds) || drivegen::check(&eds).device.is_none() {
            continue;
        }
        let alone = drivegen::check(&eds).device.unwrap();
        let checked = import_and_check(&eds, &scratch);
        let rendered = checked.render();
        let overlaid = checked
            .device
            .unwrap_or_else(|| panic!("{}:\n{rendered}", eds.display()));
        let names = |d: &drivegen::ir::Device| {
            let mut v: Vec<_> = d
                .parameters
                .iter()
                .map(|p| (p.name.clone(), p.canopen[0].index, p.canopen[0].subindex))
                .collect();
            v.sort();
            v
        };
        assert_eq!(names(&overlaid), names(&alone), "{}", eds.display());
        imported += 1;
    }
    assert!(imported >= 20, "only {imported} corpus files imported");
}

#[test]
fn an_unreadable_eds_is_not_imported() {
    let missing = Path::new("tests/eds/no_such_file.eds");
    let error = drivegen::eds::import_overlay(missing, Path::new("tests/eds/no_such_file.toml"));
    let text = error.expect_err("no file").to_string();
    assert!(text.contains("cannot read"), "{text}");
}

#[test]
fn an_imported_overlay_that_does_not_check_says_why() {
    // A default outside the EDS's own limits: the skeleton is written, and its check fails.
    let scratch = Scratch::new("eds-import-fails");
    let eds = scratch.0.join("default_outside_limits.eds");
    std::fs::copy("tests/eds/default_outside_limits.eds", &eds).unwrap();
    let imported = drivegen::eds::import_overlay(&eds, &scratch.0.join("odd.toml")).unwrap();
    assert!(!imported.checks());
    assert!(
        imported.overlay.contains("index = 0x2000"),
        "{}",
        imported.overlay
    );
    let findings = imported.checked.render();
    assert!(
        findings.contains(
            "error[defaults_within_range]: default of `speed` 5 is outside its range 10..=20"
        ),
        "{findings}"
    );
}

#[test]
fn an_unknown_data_type_is_marked_in_the_skeleton_for_the_user_to_type() {
    let scratch = Scratch::new("eds-import-vendor-type");
    let eds = scratch.0.join("data_type_vendor.eds");
    std::fs::copy("tests/eds/data_type_vendor.eds", &eds).unwrap();
    let path = scratch.0.join("data_type_vendor.toml");
    let imported = drivegen::eds::import_overlay(&eds, &path).unwrap();
    assert!(imported.checks(), "{}", imported.checked.render());
    let marked = "name = \"motor_table\"\n# DataType 0x0040 is vendor-specific or reserved: read as an octet string. Give the type the vendor documents, e.g.\n# type = \"u32\"\n";
    assert!(imported.overlay.contains(marked), "{}", imported.overlay);
    let warned = |checked: &drivegen::Checked| checked.render().contains("DataType 0x0040");
    assert!(warned(&imported.checked));
    // The user types it: the object is a u32 and the warning is gone.
    let typed = imported
        .overlay
        .replace(marked, "name = \"motor_table\"\ntype = \"u32\"\n");
    std::fs::write(&path, typed).unwrap();
    let checked = drivegen::check(&path);
    assert!(!warned(&checked), "{}", checked.render());
    let device = checked.device.expect("the typed overlay checks");
    let motor_table = device.parameters.iter().find(|p| p.name == "motor_table");
    assert_eq!(
        motor_table.map(|p| p.data_type),
        Some(drivegen::ir::DataType::Unsigned(4))
    );
}

#[test]
fn an_overlay_saved_elsewhere_names_the_eds_relative_to_it() {
    let scratch = Scratch::new("eds-import-elsewhere");
    let eds = scratch.0.join("vendor").join("minimal_var.eds");
    std::fs::create_dir_all(eds.parent().unwrap()).unwrap();
    std::fs::copy("tests/eds/minimal_var.eds", &eds).unwrap();
    let overlay = scratch.0.join("overlays").join("drive.toml");
    std::fs::create_dir_all(overlay.parent().unwrap()).unwrap();
    let imported = drivegen::eds::import_overlay(&eds, &overlay).unwrap();
    assert!(
        imported
            .overlay
            .contains("eds = \"../vendor/minimal_var.eds\""),
        "{}",
        imported.overlay
    );
    assert!(imported.checks(), "{}", imported.checked.render());
}

#[test]
fn an_overlay_adds_pdo_layouts_over_eds_objects() {
    let d = device(Path::new("tests/fixtures/overlay"));
    let layouts: Vec<_> = d
        .pdos()
        .map(|(m, _)| {
            let cob_id = m.default_cob_id().expect("a PDO has a COB-ID");
            (
                m.name.as_str(),
                cob_id.value,
                cob_id.plus_node_id,
                m.entries.clone(),
            )
        })
        .collect();
    assert_eq!(
        layouts,
        [
            ("tpdo1", 0x180, true, vec!["vendor_torque".to_owned()]),
            ("rpdo1", 0x200, true, vec!["controlword".to_owned()]),
        ]
    );
    let code = drivegen::emit::rust::generate(&d, "overlay");
    assert!(code.contains("pub struct Tpdo1"), "{code}");
    assert!(code.contains("MappedObject::new(0x2001, 0, 16)"), "{code}");
}

#[test]
fn an_overlay_pdo_entry_naming_no_eds_object_points_at_the_overlay() {
    let scratch = Scratch::new("eds-overlay-pdo");
    let fixture = Path::new("tests/fixtures/overlay");
    std::fs::copy(fixture.join("drive.eds"), scratch.0.join("drive.eds")).unwrap();
    let overlay = std::fs::read_to_string(fixture.join("device.toml"))
        .unwrap()
        .replace(
            "entries = [\"vendor_torque\"]",
            "entries = [\"vendor_torq\"]",
        );
    std::fs::write(scratch.0.join("device.toml"), overlay).unwrap();
    let checked = drivegen::check(&scratch.0);
    assert!(checked.device.is_none());
    let text = checked.render();
    assert!(
        text.contains("error[mapping_entries_are_mappable]: PDO `tpdo1` maps `vendor_torq`, which is not a parameter"),
        "{text}"
    );
    assert!(
        text.contains("device.toml:"),
        "points at the overlay: {text}"
    );
    assert!(text.contains("entries = [\"vendor_torq\"]"), "{text}");
}
