//! Changes to the device's identity, variants, enumerations and bit-flags words.

use super::{match_by_name, Change, Impact};
use crate::ir::{DataType, Device, Enum, Flags};

/// The drive handle's name and the variants (`Variant` enum) of the device.
pub(super) fn device(old: &Device, new: &Device, out: &mut Vec<Change>) {
    if old.device.handle != new.device.handle {
        out.push(Change::new(
            Impact::Breaking,
            "device",
            format!(
                "drive handle `{}` renamed to `{}`",
                old.device.handle, new.device.handle
            ),
        ));
    }
    let variants = match_by_name(&old.variants, &new.variants, |v| &v.name);
    for v in variants.removed {
        out.push(Change::new(
            Impact::Breaking,
            format!("variant `{}`", v.name),
            "removed",
        ));
    }
    for v in variants.added {
        out.push(Change::new(
            Impact::Compatible,
            format!("variant `{}`", v.name),
            "added",
        ));
    }
}

/// Open enumerations: a removed value removes its constant; a renumbered one reads differently.
pub(super) fn enums(old: &[Enum], new: &[Enum], out: &mut Vec<Change>) {
    let matched = match_by_name(old, new, |e| &e.name);
    added_and_removed("enum", &matched.removed, &matched.added, |e| &e.name, out);
    for (o, n) in matched.both {
        let subject = format!("enum `{}`", o.name);
        raw_type(&subject, o.data_type, n.data_type, out);
        let values = match_by_name(&o.values, &n.values, |v| &v.name);
        for v in values.removed {
            out.push(Change::new(
                Impact::Breaking,
                &subject,
                format!("value `{}` removed", v.name),
            ));
        }
        for v in values.added {
            out.push(Change::new(
                Impact::Compatible,
                &subject,
                format!("value `{}` = {} added", v.name, v.value),
            ));
        }
        for (ov, nv) in values.both.into_iter().filter(|(a, b)| a.value != b.value) {
            out.push(Change::new(
                Impact::Behaviour,
                &subject,
                format!("value `{}` renumbered {} → {}", ov.name, ov.value, nv.value),
            ));
        }
    }
}

/// Bit-flags words: named bits and multi-bit fields.
pub(super) fn flags(old: &[Flags], new: &[Flags], out: &mut Vec<Change>) {
    let matched = match_by_name(old, new, |f| &f.name);
    added_and_removed("flags", &matched.removed, &matched.added, |f| &f.name, out);
    for (o, n) in matched.both {
        let subject = format!("flags `{}`", o.name);
        raw_type(&subject, o.data_type, n.data_type, out);
        let bits = match_by_name(&o.bits, &n.bits, |b| &b.name);
        let positions = bits
            .both
            .iter()
            .map(|(a, b)| (a.name.as_str(), a.bit, b.bit));
        members(
            &subject,
            "bit",
            &bits.removed,
            &bits.added,
            |b| &b.name,
            positions,
            out,
        );
        let fields = match_by_name(&o.fields, &n.fields, |f| &f.name);
        let placements = fields
            .both
            .iter()
            .map(|(a, b)| (a.name.as_str(), (a.lsb, a.width), (b.lsb, b.width)));
        members(
            &subject,
            "field",
            &fields.removed,
            &fields.added,
            |f| &f.name,
            placements,
            out,
        );
    }
}

/// A new raw type changes the newtype's field and its `TryFrom` / `from_bits` input: breaking.
pub(super) fn raw_type(subject: &str, old: DataType, new: DataType, out: &mut Vec<Change>) {
    if old != new {
        out.push(Change::new(
            Impact::Breaking,
            subject,
            format!("raw type {} → {}", old.name(), new.name()),
        ));
    }
}

/// Removed (breaking) and added (compatible) whole items of one kind.
fn added_and_removed<T>(
    kind: &str,
    removed: &[&T],
    added: &[&T],
    name: impl Fn(&T) -> &str,
    out: &mut Vec<Change>,
) {
    for item in removed {
        out.push(Change::new(
            Impact::Breaking,
            format!("{kind} `{}`", name(item)),
            "removed",
        ));
    }
    for item in added {
        out.push(Change::new(
            Impact::Compatible,
            format!("{kind} `{}`", name(item)),
            "added",
        ));
    }
}

/// Removed, added and moved members (bits or fields) of one flags word.
fn members<'a, T, P: PartialEq + std::fmt::Debug>(
    subject: &str,
    kind: &str,
    removed: &[&T],
    added: &[&T],
    name: impl Fn(&T) -> &str,
    positions: impl Iterator<Item = (&'a str, P, P)>,
    out: &mut Vec<Change>,
) {
    for m in removed {
        out.push(Change::new(
            Impact::Breaking,
            subject,
            format!("{kind} `{}` removed", name(m)),
        ));
    }
    for m in added {
        out.push(Change::new(
            Impact::Compatible,
            subject,
            format!("{kind} `{}` added", name(m)),
        ));
    }
    for (member, old, new) in positions.filter(|(_, a, b)| a != b) {
        out.push(Change::new(
            Impact::Behaviour,
            subject,
            format!("{kind} `{member}` moved {old:?} → {new:?}"),
        ));
    }
}
