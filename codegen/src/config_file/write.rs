//! [`ConfigFile`] to text: one line per parameter, so an error can point at it and a person can
//! edit it.

use std::fmt::Write;

use super::{ConfigFile, SavedRaw, FORMAT_VERSION};

/// The file's text. Integers beyond 64 bits are written as decimal strings (TOML integers are
/// 64-bit signed).
pub fn render(file: &ConfigFile) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "# A drive's configuration, read by `drivegen config pull` (docs/config-file.md).\n\
         # Edit `value` (engineering units, as `drivegen write` takes it); `raw` is what was read\n\
         # and is written back while `value` is unchanged.\nformat = {FORMAT_VERSION}\n"
    );
    let d = &file.description;
    let _ = writeln!(out, "[description]\nname = {}", quoted(&d.name));
    if let Some(firmware) = &d.firmware {
        let _ = writeln!(out, "firmware = {}", quoted(firmware));
    }
    if let Some(path) = &d.path {
        let _ = writeln!(out, "path = {}", quoted(path));
    }
    let _ = writeln!(out, "\n[drive]\ntarget = {}", quoted(&file.drive.target));
    if let Some(variant) = &file.drive.variant {
        let _ = writeln!(out, "variant = {}", quoted(variant));
    }
    let _ = writeln!(out, "pulled_at = {}", quoted(&file.drive.pulled_at));
    out.push_str("\n[identity]\n");
    for entry in &file.identity {
        let _ = writeln!(out, "{} = {}", key(&entry.name), int(entry.raw));
    }
    out.push_str("\n[parameters]\n");
    for p in &file.parameters {
        let unit = p
            .unit
            .as_deref()
            .map_or(String::new(), |u| format!(", unit = {}", quoted(u)));
        let _ = writeln!(
            out,
            "{} = {{ value = {}, raw = {}{unit} }}",
            key(&p.name),
            quoted(&p.value),
            raw(&p.raw)
        );
    }
    out.push_str("\n[unread]\n");
    for u in &file.unread {
        let _ = writeln!(out, "{} = {}", key(&u.name), quoted(&u.reason));
    }
    out
}

fn quoted(text: &str) -> String {
    toml::Value::String(text.to_owned()).to_string()
}

/// A parameter name as a TOML key: bare where TOML allows it (every description name does).
fn key(name: &str) -> String {
    let bare = !name.is_empty()
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
    if bare {
        name.to_owned()
    } else {
        quoted(name)
    }
}

fn int(value: i128) -> String {
    match i64::try_from(value) {
        Ok(fits) => fits.to_string(),
        Err(_) => format!("\"{value}\""),
    }
}

fn raw(value: &SavedRaw) -> String {
    match value {
        SavedRaw::Int(value) => int(*value),
        SavedRaw::Float(value) => toml::Value::Float(*value).to_string(),
        SavedRaw::Bytes(bytes) => format!(
            "[{}]",
            bytes
                .iter()
                .map(u8::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}
