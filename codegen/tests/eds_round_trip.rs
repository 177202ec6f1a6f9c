//! TOML → EDS → IR equals TOML → IR for every shipped CANopen description and for random valid
//! ones, on the fields an EDS carries: object addresses, names, types, access, PDO mapping,
//! defaults, limits and records, plus the communication and mapping objects of the description's
//! declared PDOs. The overlay skeleton `drivegen eds import` writes for each exported EDS checks
//! as written and keeps its objects.

mod support;

use std::collections::BTreeMap;
use std::path::Path;

use drivegen::ir::{Device, Number, Parameter, Record};
use proptest::prelude::*;
use support::random_description::description;
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

/// A name as the generated code spells it. An EDS keeps a name's words, not every character:
/// `a__b` reads back as `a_b`, the same Rust identifier (names that collide there are refused).
fn rust(name: &str) -> String {
    drivegen::names::snake(name)
}

/// The CANopen view of a device, default variant only, keyed by (index, subindex).
fn canopen_view(device: &Device) -> BTreeMap<(u16, u8), Kept> {
    let default_variant = device.variants.first().map(|v| v.name.clone());
    let mut view = BTreeMap::new();
    for p in device
        .parameters
        .iter()
        .filter(|p| in_default_variant(device, p))
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
                rust(&p.name),
                p.data_type.name().to_owned(),
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

/// Whether `p` exists in the first (default) variant, the one an EDS describes.
fn in_default_variant(device: &Device, p: &Parameter) -> bool {
    let default = device.variants.first().map(|v| &v.name);
    p.variants.is_empty() || default.is_some_and(|d| p.variants.contains(d))
}

/// `drivegen eds import`'s overlay skeleton of `eds` checks as written, with the objects of the
/// EDS alone (`alone`).
fn imported_overlay_keeps_the_objects(eds: &Path, alone: &Device) -> Result<(), String> {
    let path = eds.with_extension("toml");
    let imported = drivegen::eds::import_overlay(eds, &path).map_err(|e| format!("import: {e}"))?;
    std::fs::write(&path, imported.overlay).unwrap();
    let checked = drivegen::check(&path);
    let Some(imported) = checked.device else {
        return Err(format!(
            "the imported overlay does not check:\n{}",
            checked.render()
        ));
    };
    match canopen_view(&imported) == canopen_view(alone) {
        true => Ok(()),
        false => Err("the imported overlay changes the EDS's objects".into()),
    }
}

/// The members of `record` in the default variant.
fn members<'d>(device: &'d Device, record: &'d Record) -> impl Iterator<Item = &'d Parameter> {
    let named = |p: &&Parameter| p.record.as_ref() == Some(&record.name);
    let parameters = device.parameters.iter().filter(named);
    parameters.filter(|p| in_default_variant(device, p))
}

/// Exports `original` to `eds`, reads it back and compares what an EDS carries; the first
/// difference, or a finding of the reader, is the error.
fn round_trip(original: Device, eds: &Path) -> Result<(), String> {
    std::fs::write(eds, drivegen::eds::export(&original)).unwrap();
    let checked = drivegen::check(eds);
    if !checked.diagnostics.is_empty() {
        return Err(format!(
            "the exported EDS reads with findings:\n{}",
            checked.render()
        ));
    }
    let again = checked.device.expect("no findings means a device");
    imported_overlay_keeps_the_objects(eds, &again)?;
    // What the EDS carries of the description: its objects and those its PDOs imply.
    let mut original = original;
    let derived = drivegen::eds::pdo_objects(&original);
    original.parameters.extend(derived.parameters);
    original.records.extend(derived.records);
    // A record whose members all belong to other variants is no object of the default one.
    let in_eds = |record: &&Record| members(&original, record).next().is_some();
    for record in original.records.iter().filter(in_eds) {
        let found = again.records.iter().find(|r| r.index == record.index);
        if found.map(|r| (rust(&r.name), r.kind)) != Some((rust(&record.name), record.kind)) {
            return Err(format!("record {:#06X} became {found:?}", record.index));
        }
        for member in members(&original, record) {
            let read_back = again
                .parameters
                .iter()
                .find(|p| rust(&p.name) == rust(&member.name))
                .map(|p| p.record.as_deref().map(rust));
            if read_back != Some(Some(rust(&record.name))) {
                return Err(format!("member {} is in {read_back:?}", member.name));
            }
        }
    }
    let (before, after) = (canopen_view(&original), canopen_view(&again));
    match before
        .keys()
        .chain(after.keys())
        .find(|key| before.get(key) != after.get(key))
    {
        Some(key) => Err(format!(
            "object {:#06X} sub {}: {:?} became {:?}",
            key.0,
            key.1,
            before.get(key),
            after.get(key)
        )),
        None => Ok(()),
    }
}

#[test]
fn toml_to_eds_to_ir_keeps_every_canopen_field() {
    let scratch = Scratch::new("eds-round-trip");
    for description in canopen_descriptions() {
        let original = device(&description);
        assert!(
            original.parameters.iter().any(|p| !p.canopen.is_empty()),
            "{} has CANopen objects",
            description.display()
        );
        let eds = scratch.0.join(format!("{}.eds", short_name(&description)));
        if let Err(difference) = round_trip(original, &eds) {
            panic!("{}: {difference}", description.display());
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Random valid descriptions (every type, limits, defaults, enums, flags, variants...).
    #[test]
    fn random_descriptions_keep_every_canopen_field_through_an_eds(text in description()) {
        let scratch = Scratch::new("eds-round-trip-random");
        let path = scratch.0.join("device.toml");
        std::fs::write(&path, &text).unwrap();
        if let Some(original) = drivegen::check(&path).device {
            let result = round_trip(original, &scratch.0.join("random.eds"));
            prop_assert!(result.is_ok(), "{}\n{}", result.unwrap_err(), text);
        }
    }
}
