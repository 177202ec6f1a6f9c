//! TOML → EDS → IR equals TOML → IR for every shipped CANopen description, on the fields an EDS
//! carries: object addresses, names, types, access, PDO mapping, defaults, limits and records,
//! plus the communication and mapping objects of the description's declared PDOs.

mod support;

use std::collections::BTreeMap;

use drivegen::ir::{Device, Number};
use support::{canopen_descriptions, device, short_name, Scratch};

/// What an EDS keeps of one object: name, type name, access, constant, PDO, default, range.
type Kept = (
    String,
    String,
    String,
    bool,
    String,
    Option<String>,
    Option<String>,
);

fn number(n: Number) -> String {
    format!("{n:?}")
}

/// The CANopen view of a device, default variant only, keyed by (index, subindex).
fn canopen_view(device: &Device) -> BTreeMap<(u16, u8), Kept> {
    let default_variant = device.variants.first().map(|v| v.name.clone());
    let mut view = BTreeMap::new();
    for p in device
        .parameters
        .iter()
        .filter(|p| p.variants.is_empty() || p.variants.first() == default_variant.as_ref())
    {
        for a in p
            .canopen
            .iter()
            .filter(|a| a.variant.is_none() || a.variant == default_variant)
        {
            let default = p.default.map(|d| {
                format!(
                    "{}{}",
                    if p.default_plus_node_id {
                        "$NODEID+"
                    } else {
                        ""
                    },
                    number(d)
                )
            });
            let range = p
                .range
                .as_ref()
                .map(|r| format!("{}..={}", number(r.min), number(r.max)));
            view.entry((a.index, a.subindex)).or_insert((
                p.name.clone(),
                p.data_type.name(),
                format!("{:?}", a.access),
                a.constant,
                format!("{:?}", a.pdo),
                default,
                range,
            ));
        }
    }
    view
}

#[test]
fn toml_to_eds_to_ir_keeps_every_canopen_field() {
    let scratch = Scratch::new("eds-round-trip");
    for description in canopen_descriptions() {
        let original = device(&description);
        let eds = scratch.0.join(format!("{}.eds", short_name(&description)));
        std::fs::write(&eds, drivegen::eds::export(&original)).unwrap();
        let checked = drivegen::check(&eds);
        assert!(
            checked.diagnostics.is_empty(),
            "{}: the exported EDS reads with findings:\n{}",
            description.display(),
            checked.render()
        );
        let again = checked.device.expect("no findings means a device");
        // What the EDS carries of the description: its objects and those its PDOs imply.
        let mut original = original;
        let derived = drivegen::eds::pdo_objects(&original);
        original.parameters.extend(derived.parameters);
        original.records.extend(derived.records);
        let (before, after) = (canopen_view(&original), canopen_view(&again));
        assert!(
            !before.is_empty(),
            "{} has CANopen objects",
            description.display()
        );
        for record in &original.records {
            let found = again.records.iter().find(|r| r.index == record.index);
            assert_eq!(
                found.map(|r| (&r.name, r.kind)),
                Some((&record.name, record.kind)),
                "{}: record {:#06X}",
                description.display(),
                record.index
            );
            for member in original
                .parameters
                .iter()
                .filter(|p| p.record.as_ref() == Some(&record.name))
            {
                let read_back = again.parameter(&member.name).map(|p| &p.record);
                assert_eq!(
                    read_back,
                    Some(&member.record),
                    "{}: member {}",
                    description.display(),
                    member.name
                );
            }
        }
        for key in before.keys().chain(after.keys()) {
            assert_eq!(
                before.get(key),
                after.get(key),
                "{}: object {:#06X} sub {}",
                description.display(),
                key.0,
                key.1
            );
        }
    }
}
