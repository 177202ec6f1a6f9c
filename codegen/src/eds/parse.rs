//! The INI layer of an EDS / DCF: sections and `key=value` entries with spans, nothing interpreted.
//!
//! Lenient by design: section and key names are compared lower-case, `;` starts a comment (at the
//! start of a line, or after white space as python's `configparser` reads it), duplicate sections
//! merge and duplicate keys keep the first value, both with a warning.

use fnv::FnvHashMap;

use crate::diagnostic::{Diagnostic, FileId, Span};

const RULE: &str = "eds_syntax";

/// One `key=value` line, borrowed from the file text.
#[derive(Debug, Clone)]
pub struct Entry<'t> {
    /// The key as written (compare it with [`Entry::is`]).
    pub key: &'t str,
    /// The key as written.
    pub key_span: Span,
    /// The value, trimmed, comment removed.
    pub value: &'t str,
    /// Where the value is written.
    pub value_span: Span,
}

impl Entry<'_> {
    /// Whether the key is `lower` (a lower-case name), in any case.
    pub fn is(&self, lower: &str) -> bool {
        self.key.eq_ignore_ascii_case(lower)
    }
}

/// One `[section]` with its entries.
#[derive(Debug, Clone)]
pub struct Section<'t> {
    /// The name, lower-case.
    pub name: String,
    /// The header `[...]`.
    pub span: Span,
    /// Entries in file order, keys unique regardless of case.
    pub entries: Vec<Entry<'t>>,
}

impl<'t> Section<'t> {
    /// The entry of a lower-case key.
    pub fn get(&self, key: &str) -> Option<&Entry<'t>> {
        self.entries.iter().find(|e| e.is(key))
    }
}

/// A whole file: sections in file order, names unique.
#[derive(Debug, Default, Clone)]
pub struct Ini<'t> {
    /// Sections.
    pub sections: Vec<Section<'t>>,
    /// Lower-case name → position in `sections` (vendor files have thousands of sections).
    by_name: FnvHashMap<String, usize>,
}

impl<'t> Ini<'t> {
    /// The section of a lower-case name.
    pub fn section(&self, name: &str) -> Option<&Section<'t>> {
        self.by_name.get(name).map(|&i| &self.sections[i])
    }
}

/// Splits `text` into sections; problems are warnings pushed to `diagnostics`.
pub fn parse_ini<'t>(file: FileId, text: &'t str, diagnostics: &mut Vec<Diagnostic>) -> Ini<'t> {
    let headers = text.bytes().filter(|&b| b == b'[').count();
    let mut ini = Ini {
        sections: Vec::with_capacity(headers),
        by_name: FnvHashMap::with_capacity_and_hasher(headers, Default::default()),
    };
    let mut current: Option<usize> = None;
    let mut offset = 0;
    for raw_line in text.split_inclusive('\n') {
        let start = offset;
        offset += raw_line.len();
        let line = strip_comment(raw_line.trim_end_matches(['\n', '\r']));
        let trimmed = line.trim();
        if trimmed.is_empty() {
            continue;
        }
        let lead = line.len() - line.trim_start().len();
        let span = Span::new(file, start + lead..start + lead + trimmed.len());
        if let Some(name) = trimmed.strip_prefix('[').and_then(|t| t.strip_suffix(']')) {
            current = Some(open_section(&mut ini, name.trim(), span, diagnostics));
        } else if let Some(eq) = trimmed.find('=') {
            let Some(section) = current else {
                diagnostics.push(
                    Diagnostic::error(RULE, span, "entry outside any section is ignored").warning(),
                );
                continue;
            };
            let entry = entry(file, start + lead, trimmed, eq);
            add_entry(&mut ini.sections[section], entry, diagnostics);
        } else {
            diagnostics.push(
                Diagnostic::error(
                    RULE,
                    span,
                    "line is neither a `[section]`, a `key=value` nor a comment; ignored",
                )
                .warning(),
            );
        }
    }
    ini
}

/// Removes a `;` comment: a whole-line one, or one preceded by white space.
fn strip_comment(line: &str) -> &str {
    if line.trim_start().starts_with(';') {
        return "";
    }
    let bytes = line.as_bytes();
    (1..bytes.len())
        .find(|&i| bytes[i] == b';' && bytes[i - 1].is_ascii_whitespace())
        .map_or(line, |i| &line[..i])
}

fn open_section(
    ini: &mut Ini<'_>,
    name: &str,
    span: Span,
    diagnostics: &mut Vec<Diagnostic>,
) -> usize {
    let lower = name.to_ascii_lowercase();
    if let Some(&i) = ini.by_name.get(&lower) {
        diagnostics.push(
            Diagnostic::error(RULE, span, format!("section `[{name}]` appears twice"))
                .warning()
                .label("its entries are merged into the first one")
                .help("CANopen tools (python canopen among them) refuse duplicate sections"),
        );
        return i;
    }
    ini.by_name.insert(lower.clone(), ini.sections.len());
    ini.sections.push(Section {
        name: lower,
        span,
        entries: Vec::with_capacity(8),
    });
    ini.sections.len() - 1
}

fn entry(file: FileId, line_start: usize, line: &str, eq: usize) -> Entry<'_> {
    let key = &line[..eq];
    let key_trimmed = key.trim_end();
    let value_raw = &line[eq + 1..];
    let value = value_raw.trim();
    let value_start = line_start + eq + 1 + (value_raw.len() - value_raw.trim_start().len());
    Entry {
        key: key_trimmed,
        key_span: Span::new(file, line_start..line_start + key_trimmed.len()),
        value,
        value_span: Span::new(file, value_start..value_start + value.len()),
    }
}

fn add_entry<'t>(section: &mut Section<'t>, entry: Entry<'t>, diagnostics: &mut Vec<Diagnostic>) {
    if section
        .entries
        .iter()
        .any(|e| e.key.eq_ignore_ascii_case(entry.key))
    {
        diagnostics.push(
            Diagnostic::error(RULE, entry.key_span, "key appears twice in its section")
                .warning()
                .label("this later value is ignored"),
        );
        return;
    }
    section.entries.push(entry);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sections_and_keys_are_case_insensitive_and_comments_are_dropped() {
        let mut d = Vec::new();
        let ini = parse_ini(
            FileId(0),
            "; head\n[DeviceInfo]\nVendorName=ACME ; trailing\nx;y=1\n",
            &mut d,
        );
        let s = ini.section("deviceinfo").unwrap();
        assert_eq!(s.get("vendorname").unwrap().value, "ACME");
        assert_eq!(s.get("x;y").unwrap().value, "1");
        assert!(d.is_empty());
    }

    #[test]
    fn duplicates_and_stray_lines_are_warnings() {
        let mut d = Vec::new();
        let ini = parse_ini(FileId(0), "k=1\n[A]\nk=1\nK=2\n[a]\nj=3\ngarbage\n", &mut d);
        assert_eq!(ini.sections.len(), 1);
        assert_eq!(ini.sections[0].entries.len(), 2);
        assert_eq!(d.len(), 4);
    }
}
