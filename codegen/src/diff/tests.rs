use super::{diff, render, Impact};
use crate::validate::test_support::device;

const ENUM: &str = r#"
[[enum]]
name = "mode"
type = "u16"
values = [ { name = "off", value = 0 }, { name = "on", value = 1 } ]
source = { doc = "m", line = 3 }
"#;

fn param(extra: &str) -> String {
    format!(
        "[[parameter]]\nname = \"speed\"\ntype = \"u16\"\nsource = {{ doc = \"m\", line = 1 }}\n{extra}\n"
    )
}

/// `(impact, what)` of every change from `old` to `new`.
fn changes(old: &str, new: &str) -> Vec<(Impact, String)> {
    diff(&device(old), &device(new))
        .into_iter()
        .map(|c| (c.impact, format!("{}: {}", c.subject, c.what)))
        .collect()
}

#[test]
fn identical_descriptions_have_no_changes() {
    let p = param("modbus = { table = \"holding\", address = 0x10 }");
    assert!(changes(&p, &p).is_empty());
    assert_eq!(render(&[]), "no changes\n");
}

#[test]
fn a_removed_parameter_breaks_and_an_added_one_does_not() {
    let other = "[[parameter]]\nname = \"torque\"\ntype = \"i16\"\nmodbus = { table = \"input\", address = 0x20 }\nsource = { doc = \"m\", line = 2 }\n";
    let base = param("modbus = { table = \"holding\", address = 0x10 }");
    assert_eq!(
        changes(&format!("{base}{other}"), &base),
        [(Impact::Breaking, "parameter `torque`: removed".into())]
    );
    assert_eq!(
        changes(&base, &format!("{base}{other}")),
        [(Impact::Compatible, "parameter `torque`: added".into())]
    );
}

#[test]
fn a_new_unit_or_raw_type_breaks() {
    let old = param("unit = \"rpm\"\nmodbus = { table = \"holding\", address = 0x10 }");
    let new = param("unit = \"Hz\"\nmodbus = { table = \"holding\", address = 0x10 }");
    assert_eq!(
        changes(&old, &new),
        [(
            Impact::Breaking,
            "parameter `speed`: value type `Rpm` → `Hertz`".into()
        )]
    );
    let wider = new.replace("type = \"u16\"", "type = \"u32\"");
    let found = changes(&new, &wider);
    assert!(
        found.contains(&(
            Impact::Breaking,
            "parameter `speed`: raw type u16 → u32".into()
        )),
        "{found:?}"
    );
}

#[test]
fn losing_write_access_breaks_gaining_canopen_does_not_and_a_moved_register_is_behaviour() {
    let old = param("modbus = { table = \"holding\", address = 0x10 }");
    let read_only = param("modbus = { table = \"holding\", address = 0x10, access = \"r\" }");
    assert_eq!(
        changes(&old, &read_only),
        [(
            Impact::Breaking,
            "parameter `speed`: no longer writable over Modbus".into()
        )]
    );
    let with_canopen = param("modbus = { table = \"holding\", address = 0x10 }\ncanopen = { index = 0x2000, access = \"ro\" }");
    assert_eq!(
        changes(&old, &with_canopen),
        [(
            Impact::Compatible,
            "parameter `speed`: now readable over CANopen".into()
        )]
    );
    let moved = param("modbus = { table = \"holding\", address = 0x11 }");
    let found = changes(&old, &moved);
    assert_eq!(found.len(), 2, "{found:?}");
    assert!(
        found.iter().all(|(impact, _)| *impact == Impact::Behaviour),
        "{found:?}"
    );
    assert!(
        found[0].1.contains("holding 0x0010 → holding 0x0011"),
        "{found:?}"
    );
}

#[test]
fn scale_range_and_default_changes_are_behaviour() {
    let old = param("unit = \"rpm\"\nscale = \"1/10\"\nrange = [0, 100]\ndefault = 5\nmodbus = { table = \"holding\", address = 0x10 }");
    let new = param("unit = \"rpm\"\nscale = \"1/100\"\nrange = [0, 50]\ndefault = 6\nmodbus = { table = \"holding\", address = 0x10 }");
    let found = changes(&old, &new);
    assert_eq!(
        found,
        [
            (
                Impact::Behaviour,
                "parameter `speed`: scale 1/10 → 1/100".into()
            ),
            (
                Impact::Behaviour,
                "parameter `speed`: range 0..=100 → 0..=50".into()
            ),
            (Impact::Behaviour, "parameter `speed`: default 5 → 6".into()),
        ]
    );
}

#[test]
fn enum_values_removed_break_added_are_compatible_renumbered_are_behaviour() {
    let uses = param("enum = \"mode\"\nmodbus = { table = \"holding\", address = 0x10 }");
    let old = format!("{ENUM}{uses}");
    let new = old.replace("{ name = \"off\", value = 0 }, ", "").replace(
        "{ name = \"on\", value = 1 }",
        "{ name = \"on\", value = 2 }, { name = \"auto\", value = 3 }",
    );
    let found = changes(&old, &new);
    assert_eq!(
        found,
        [
            (Impact::Breaking, "enum `mode`: value `off` removed".into()),
            (
                Impact::Behaviour,
                "enum `mode`: value `on` renumbered 1 → 2".into()
            ),
            (
                Impact::Compatible,
                "enum `mode`: value `auto` = 3 added".into()
            ),
        ]
    );
    let text = render(&diff(&device(&old), &device(&new)));
    assert!(
        text.starts_with("breaking (1):\n  enum `mode`: value `off` removed\n"),
        "{text}"
    );
    assert!(text.ends_with("3 change(s), 1 breaking\n"), "{text}");
}

#[test]
fn pdo_entries_changed_break_and_a_new_cob_id_is_behaviour() {
    let status = "[[parameter]]\nname = \"status\"\ntype = \"u16\"\ncanopen = { index = 0x6041, pdo = \"tx\" }\nsource = { doc = \"m\", line = 1 }\n[[parameter]]\nname = \"position\"\ntype = \"i32\"\ncanopen = { index = 0x6064, pdo = \"tx\" }\nsource = { doc = \"m\", line = 2 }\n";
    let pdo = |entries: &str, cob: &str| {
        format!("{status}[[pdo]]\nname = \"tpdo1\"\ndirection = \"tx\"\nnumber = 1\ncob_id = \"{cob}\"\nentries = {entries}\nsource = {{ doc = \"m\", line = 3 }}\n")
    };
    let old = pdo("[\"status\"]", "$NODEID+0x180");
    assert_eq!(
        changes(&old, &pdo("[\"status\", \"position\"]", "$NODEID+0x180")),
        [(
            Impact::Breaking,
            "PDO `tpdo1`: entries status → status, position".into()
        )]
    );
    let moved = changes(&old, &pdo("[\"status\"]", "$NODEID+0x280"));
    assert_eq!(moved.len(), 1, "{moved:?}");
    assert_eq!(moved[0].0, Impact::Behaviour);
    assert!(
        moved[0].1.contains("COB-ID 0x180 + node id") && moved[0].1.contains("0x280"),
        "{moved:?}"
    );
}
