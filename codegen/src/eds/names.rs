//! snake_case names derived from EDS `ParameterName`s, made unique among an EDS's entries.
//!
//! A large EDS has thousands of entries, most of them record members with the same few names
//! (`highest_sub_index_supported`, `cob_id`...), so names are built in one shared string and
//! each entry's final name is allocated once, after the clashes are known.

use std::collections::hash_map::Entry;
use std::fmt::Write as _;
use std::ops::Range;

use super::word_hash::WordMap;

/// A snake_case identifier from an EDS name: ASCII letters, digits and single underscores; a word
/// starts at every non-alphanumeric run, at a lower-case or digit to upper-case step, and at the
/// last capital of an acronym followed by lower case (`VendorID` → `vendor_id`).
pub fn snake_name(text: &str) -> String {
    let mut out = String::with_capacity(text.len() + 2);
    push_snake_name(&mut out, text);
    out
}

/// Appends the [`snake_name`] of `text` to `out`.
fn push_snake_name(out: &mut String, text: &str) {
    let start = out.len();
    // Bytes rather than chars: every byte of a multi-byte character is a non-alphanumeric
    // separator, exactly as the character itself would be, and bytes are cheaper to walk.
    let bytes = text.as_bytes();
    let mut after_underscore = false;
    let mut prev: Option<u8> = None;
    for (i, &c) in bytes.iter().enumerate() {
        if !c.is_ascii_alphanumeric() {
            prev = None;
            if out.len() > start && !after_underscore {
                out.push('_');
                after_underscore = true;
            }
            continue;
        }
        let next_lower = bytes.get(i + 1).is_some_and(u8::is_ascii_lowercase);
        let starts_word = c.is_ascii_uppercase()
            && prev.is_some_and(|p| {
                p.is_ascii_lowercase()
                    || p.is_ascii_digit()
                    || (p.is_ascii_uppercase() && next_lower)
            });
        if starts_word && !after_underscore {
            out.push('_');
        }
        out.push(char::from(c.to_ascii_lowercase()));
        after_underscore = false;
        prev = Some(c);
    }
    if after_underscore {
        out.pop();
    }
    match out.as_bytes().get(start) {
        None => out.push_str("object"),
        Some(c) if c.is_ascii_digit() => out.insert(start, 'n'),
        Some(_) => {}
    }
}

/// Names written one after another into one string.
#[derive(Default)]
pub struct NameList {
    text: String,
    ends: Vec<usize>,
    /// Where the snake name of each text seen so far was written: records repeat the same
    /// member names hundreds of times, and a copy costs less than deriving the name again.
    snakes: WordMap<Box<str>, Range<usize>>,
}

impl NameList {
    /// Room for `count` names of `bytes` bytes in all (growing the shared text copies it).
    pub fn with_capacity(count: usize, bytes: usize) -> Self {
        NameList {
            text: String::with_capacity(bytes),
            ends: Vec::with_capacity(count),
            snakes: WordMap::default(),
        }
    }

    /// Adds the [`snake_name`] of `text`.
    pub fn push_snake(&mut self, text: &str) {
        let start = self.text.len();
        match self.snakes.get(text) {
            // Byte by byte (`String::extend_from_within` is too recent for our MSRV): snake
            // names are ASCII, so each byte is a whole character.
            Some(earlier) => {
                for at in earlier.clone() {
                    let byte = self.text.as_bytes()[at];
                    self.text.push(char::from(byte));
                }
            }
            None => {
                push_snake_name(&mut self.text, text);
                self.snakes.insert(text.into(), start..self.text.len());
            }
        }
        self.ends.push(self.text.len());
    }

    /// The `i`-th name.
    pub fn get(&self, i: usize) -> &str {
        &self.text[self.range(i)]
    }

    fn range(&self, i: usize) -> Range<usize> {
        let start = if i == 0 { 0 } else { self.ends[i - 1] };
        start..self.ends[i]
    }

    fn iter(&self) -> impl Iterator<Item = &str> {
        (0..self.ends.len()).map(|i| self.get(i))
    }

    /// Adds a name written by `write`.
    fn push_with(&mut self, write: impl FnOnce(&mut String)) {
        write(&mut self.text);
        self.ends.push(self.text.len());
    }
}

/// What tells apart entries whose snake_case names clash.
pub struct Address<'a> {
    /// The name of the record the entry is a member of.
    pub record: Option<&'a str>,
    /// Object index.
    pub index: u16,
    /// Sub-index.
    pub subindex: u8,
}

/// The final names of entries whose snake_case names are `snakes` and whose addresses `address`
/// gives: members sharing a name get their record's name in front, then any remaining clash its
/// address (`{name}_{index:04x}_{subindex}`).
pub fn unique_names<'a>(snakes: &NameList, address: impl Fn(usize) -> Address<'a>) -> Vec<String> {
    let first = repeated(snakes.iter());
    // Names only change where they clash; without a clash they are unique as they are.
    if !first.contains(&true) {
        return snakes.iter().map(str::to_owned).collect();
    }
    let prefixes = first.iter().enumerate().filter(|&(_, &clash)| clash);
    let prefixes = prefixes.filter_map(|(i, _)| address(i).record.map(|r| r.len() + 1));
    let bytes = snakes.text.len() + prefixes.sum::<usize>();
    let mut prefixed = NameList::with_capacity(first.len(), bytes);
    for (i, &clash) in first.iter().enumerate() {
        prefixed.push_with(|out| {
            if let Some(record) = address(i).record.filter(|_| clash) {
                out.push_str(record);
                out.push('_');
            }
            out.push_str(snakes.get(i));
        });
    }
    let second = repeated(prefixed.iter());
    let names = prefixed.iter().zip(second).enumerate();
    names
        .map(|(i, (name, clash))| {
            let mut out = name.to_owned();
            if clash {
                let a = address(i);
                let _ = write!(out, "_{:04x}_{}", a.index, a.subindex);
            }
            out
        })
        .collect()
}

/// For each name, whether another item has it too. One map lookup per name: the map remembers
/// where a name was first seen, and a second sighting marks both.
pub fn repeated<'n>(names: impl Iterator<Item = &'n str>) -> Vec<bool> {
    let mut first_seen: WordMap<&str, usize> =
        WordMap::with_capacity_and_hasher(names.size_hint().0, Default::default());
    let mut clash = Vec::with_capacity(names.size_hint().0);
    for (i, name) in names.enumerate() {
        match first_seen.entry(name) {
            Entry::Occupied(first) => {
                clash[*first.get()] = true;
                clash.push(true);
            }
            Entry::Vacant(slot) => {
                slot.insert(i);
                clash.push(false);
            }
        }
    }
    clash
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_become_snake_case_identifiers() {
        assert_eq!(snake_name("Vendor-ID"), "vendor_id");
        assert_eq!(
            snake_name("Highest sub-index supported"),
            "highest_sub_index_supported"
        );
        assert_eq!(snake_name("2nd Temp (°C)"), "n2nd_temp_c");
        assert_eq!(snake_name("µ"), "object");
        assert_eq!(snake_name("VendorID"), "vendor_id");
        assert_eq!(snake_name("TPDO1 COB-ID"), "tpdo1_cob_id");
        assert_eq!(snake_name("Axis1Speed"), "axis1_speed");
        assert_eq!(snake_name("Température moteur"), "temp_rature_moteur");
        assert_eq!(snake_name("__"), "object");
        assert_eq!(snake_name("Speed (rpm) "), "speed_rpm");
    }

    #[test]
    fn names_in_a_list_are_made_like_alone() {
        let mut list = NameList::default();
        for text in ["2nd", "__", "Vendor-ID", "", "2nd", "Vendor-ID"] {
            list.push_snake(text);
        }
        let names: Vec<_> = list.iter().collect();
        assert_eq!(
            names,
            ["n2nd", "object", "vendor_id", "object", "n2nd", "vendor_id"]
        );
    }

    #[test]
    fn clashes_get_their_record_then_their_address() {
        let mut list = NameList::default();
        for text in ["Speed", "Count", "Count", "Count", "A Count"] {
            list.push_snake(text);
        }
        let records = [None, Some("a"), Some("b"), None, None];
        let names = unique_names(&list, |i| Address {
            record: records[i],
            index: 0x2000 + i as u16,
            subindex: 1,
        });
        assert_eq!(
            names,
            [
                "speed",
                "a_count_2001_1",
                "b_count",
                "count",
                "a_count_2004_1"
            ]
        );
    }
}
