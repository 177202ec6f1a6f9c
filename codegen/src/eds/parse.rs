//! The INI layer of an EDS / DCF: sections and `key=value` entries with spans, nothing interpreted.
//!
//! Lenient by design: section and key names are compared lower-case, `;` starts a comment (at the
//! start of a line, or after white space as python's `configparser` reads it), duplicate sections
//! merge and duplicate keys keep the first value, both with a warning.

use std::collections::hash_map::Entry as MapEntry;
use std::ops::Range;

use super::trim::{trim_end, trim_start};
use super::word_hash::{Caseless, WordMap};
use crate::diagnostic::{Diagnostic, FileId, Span};

const RULE: &str = "eds_syntax";

/// One `key=value` line, borrowed from the file text. Offsets instead of spans keep it small:
/// a large EDS has tens of thousands of entries.
#[derive(Debug, Clone)]
pub struct Entry<'t> {
    /// The key as written (compare it with [`Entry::is`]).
    pub key: &'t str,
    /// The value, trimmed, comment removed.
    pub value: &'t str,
    file: FileId,
    key_at: u32,
    value_at: u32,
}

impl Entry<'_> {
    /// Whether the key is `lower` (a lower-case name), in any case.
    pub fn is(&self, lower: &str) -> bool {
        self.key.eq_ignore_ascii_case(lower)
    }

    /// Where the key is written.
    pub fn key_span(&self) -> Span {
        span(self.file, self.key_at, self.key)
    }

    /// Where the value is written.
    pub fn value_span(&self) -> Span {
        span(self.file, self.value_at, self.value)
    }
}

fn span(file: FileId, at: u32, text: &str) -> Span {
    let start = at as usize;
    Span::new(file, start..start + text.len())
}

/// One `[section]` with its entries: a view into an [`Ini`].
#[derive(Debug, Clone, Copy)]
pub struct Section<'i, 't> {
    /// The name as written (compare it regardless of ASCII case).
    pub name: &'t str,
    /// The header `[...]`.
    pub span: &'i Span,
    /// The 1-based line of the header.
    pub line: u32,
    /// Entries in file order, keys unique regardless of case.
    pub entries: &'i [Entry<'t>],
}

impl<'i, 't> Section<'i, 't> {
    /// The entry of a lower-case key.
    pub fn get(&self, key: &str) -> Option<&'i Entry<'t>> {
        self.entries.iter().find(|e| e.is(key))
    }
}

/// A section header and where its entries are in [`Ini::entries`].
#[derive(Debug, Clone)]
struct Header<'t> {
    name: &'t str,
    span: Span,
    line: u32,
    entries: Range<usize>,
}

/// A whole file: sections in file order, names unique regardless of ASCII case. The entries of
/// all sections are kept in one vector (a large EDS has thousands of sections of a handful of
/// entries each).
#[derive(Debug, Default, Clone)]
pub struct Ini<'t> {
    headers: Vec<Header<'t>>,
    entries: Vec<Entry<'t>>,
    /// Header by name, in any ASCII case: keyed by the names as written rather than lower-cased
    /// copies (copying thousands of names cost more than the lookups).
    by_name: WordMap<Caseless<'t>, usize>,
}

impl<'t> Ini<'t> {
    /// The sections in file order.
    pub fn sections(&self) -> impl ExactSizeIterator<Item = Section<'_, 't>> + '_ {
        self.headers.iter().map(|h| self.view(h))
    }

    /// The section of a name, in any ASCII case.
    pub fn section(&self, name: &str) -> Option<Section<'_, 't>> {
        let i = *self.by_name.get(&Caseless(name))?;
        Some(self.view(&self.headers[i]))
    }

    fn view<'i>(&'i self, header: &'i Header<'t>) -> Section<'i, 't> {
        Section {
            name: header.name,
            span: &header.span,
            line: header.line,
            entries: &self.entries[header.entries.clone()],
        }
    }
}

/// The INI being read: entries are appended as they come, in runs (one per section header); a
/// section that appears twice gets its runs grouped at the end.
struct Reader<'t> {
    ini: Ini<'t>,
    /// The runs read so far: section and entries.
    runs: Vec<(usize, Range<usize>)>,
    /// The run of entries being read.
    current: Option<Run>,
    /// Whether a section was reopened by a duplicate header.
    reopened: bool,
}

/// The entries under one section header.
#[derive(Clone, Copy)]
struct Run {
    /// The section they belong to.
    section: usize,
    /// Where the run starts in the entries.
    start: usize,
    /// Whether the header repeats an earlier one, so the section has entries before this run.
    reopens: bool,
}

/// Splits `text` into sections; problems are warnings pushed to `diagnostics`.
pub fn parse_ini<'t>(file: FileId, text: &'t str, diagnostics: &mut Vec<Diagnostic>) -> Ini<'t> {
    if u32::try_from(text.len()).is_err() {
        let message = "an EDS of 4 GiB or more is not read";
        diagnostics.push(Diagnostic::error(RULE, Span::new(file, 0..0), message));
        return Ini::default();
    }
    let (headers, entries) = count_brackets_and_equals(text.as_bytes());
    let mut reader = Reader {
        ini: Ini {
            headers: Vec::with_capacity(headers),
            entries: Vec::with_capacity(entries),
            by_name: WordMap::with_capacity_and_hasher(headers, Default::default()),
        },
        runs: Vec::with_capacity(headers),
        current: None,
        reopened: false,
    };
    let mut next_line = 0;
    let mut line_number = 0u32;
    while next_line < text.len() {
        let line = Line::scan(text, next_line);
        next_line = line.end + 1;
        line_number = line_number.saturating_add(1);
        let Some((start, content)) = line.content(text) else {
            continue;
        };
        let span = Span::new(file, start..start + content.len());
        if let Some(name) = content.strip_prefix('[').and_then(|t| t.strip_suffix(']')) {
            let name = trim_end(trim_start(name));
            reader.open_section(name, span, line_number, diagnostics);
        } else if let Some(eq) = line.eq {
            reader.add_entry(entry(file, start, content, eq - start), span, diagnostics);
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
    reader.finish()
}

/// How often `[` and `=` occur in `bytes` (upper bounds for the sections and entries to make room
/// for). Counting into bytes per chunk of 255 lets the compiler use wide vector adds.
fn count_brackets_and_equals(bytes: &[u8]) -> (usize, usize) {
    bytes.chunks(255).fold((0, 0), |(brackets, equals), chunk| {
        let (b, e) = chunk.iter().fold((0u8, 0u8), |(b, e), &byte| {
            (b + u8::from(byte == b'['), e + u8::from(byte == b'='))
        });
        (brackets + usize::from(b), equals + usize::from(e))
    })
}

impl<'t> Reader<'t> {
    fn open_section(
        &mut self,
        name: &'t str,
        span: Span,
        line: u32,
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        self.close_run();
        let run_start = self.ini.entries.len();
        let i = self.ini.headers.len();
        match self.ini.by_name.entry(Caseless(name)) {
            MapEntry::Vacant(slot) => slot.insert(i),
            MapEntry::Occupied(first) => {
                let first = *first.get();
                self.reopen(first, name, span, run_start, diagnostics);
                return;
            }
        };
        self.ini.headers.push(Header {
            name,
            span,
            line,
            entries: 0..0,
        });
        self.current = Some(Run {
            section: i,
            start: run_start,
            reopens: false,
        });
    }

    /// A header repeating section `i`'s: its entries are merged into that section.
    fn reopen(
        &mut self,
        i: usize,
        name: &str,
        span: Span,
        run_start: usize,
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        diagnostics.push(
            Diagnostic::error(RULE, span, format!("section `[{name}]` appears twice"))
                .warning()
                .label("its entries are merged into the first one")
                .help("CANopen tools (python canopen among them) refuse duplicate sections"),
        );
        self.reopened = true;
        self.current = Some(Run {
            section: i,
            start: run_start,
            reopens: true,
        });
    }

    fn add_entry(&mut self, entry: Entry<'t>, line: Span, diagnostics: &mut Vec<Diagnostic>) {
        let Some(run) = self.current else {
            diagnostics.push(
                Diagnostic::error(RULE, line, "entry outside any section is ignored").warning(),
            );
            return;
        };
        let same_key = |e: &Entry| e.key.eq_ignore_ascii_case(entry.key);
        let in_run = self.ini.entries[run.start..].iter().any(same_key);
        // Only a reopened section has entries before its current run (rare: a full scan is fine).
        let earlier = || {
            let runs = self
                .runs
                .iter()
                .filter(|(section, _)| *section == run.section);
            runs.flat_map(|(_, entries)| &self.ini.entries[entries.clone()])
                .any(same_key)
        };
        if in_run || (run.reopens && earlier()) {
            diagnostics.push(
                Diagnostic::error(RULE, entry.key_span(), "key appears twice in its section")
                    .warning()
                    .label("this later value is ignored"),
            );
            return;
        }
        self.ini.entries.push(entry);
    }

    /// Ends the run being read, if any.
    fn close_run(&mut self) {
        if let Some(run) = self.current.take() {
            let entries = run.start..self.ini.entries.len();
            self.runs.push((run.section, entries));
        }
    }

    /// Records where each section's entries are, grouping the runs of a reopened section.
    fn finish(mut self) -> Ini<'t> {
        self.close_run();
        if !self.reopened {
            for (section, entries) in self.runs {
                self.ini.headers[section].entries = entries;
            }
            return self.ini;
        }
        // Stable: a section's runs stay in file order.
        self.runs.sort_by_key(|&(section, _)| section);
        let mut grouped = Vec::with_capacity(self.ini.entries.len());
        let mut previous = None;
        for (section, entries) in self.runs {
            let start = grouped.len();
            grouped.extend_from_slice(&self.ini.entries[entries]);
            let range = &mut self.ini.headers[section].entries;
            if previous == Some(section) {
                range.end = grouped.len();
            } else {
                *range = start..grouped.len();
            }
            previous = Some(section);
        }
        self.ini.entries = grouped;
        self.ini
    }
}

/// One line's landmarks, found in a single pass over its bytes (offsets into the whole text).
struct Line {
    /// Where the line starts.
    start: usize,
    /// Its `\n`, or the end of the text.
    end: usize,
    /// The first `=` before any comment.
    eq: Option<usize>,
    /// A `;` preceded by white space: a comment to the end of the line.
    comment: Option<usize>,
}

impl Line {
    /// Scans the line of `text` starting at `start`.
    fn scan(text: &str, start: usize) -> Self {
        let bytes = text.as_bytes();
        let mut line = Line {
            start,
            end: start,
            eq: None,
            comment: None,
        };
        while let Some(at) = next_landmark(bytes, line.end) {
            line.end = at;
            match bytes[at] {
                b'\n' => return line,
                _ if line.comment.is_some() => {}
                b'=' if line.eq.is_none() => line.eq = Some(at),
                b';' if at > start && bytes[at - 1].is_ascii_whitespace() => {
                    line.comment = Some(at)
                }
                _ => {}
            }
            line.end += 1;
        }
        line.end = bytes.len();
        line
    }

    /// What the line says, with where it starts: its text without a `;` comment (a whole-line
    /// one, or one preceded by white space) and surrounding white space; `None` when nothing is
    /// left.
    fn content<'t>(&self, text: &'t str) -> Option<(usize, &'t str)> {
        let line = &text[self.start..self.end];
        let trimmed = trim_start(line);
        if trimmed.as_bytes().first().is_none_or(|&b| b == b';') {
            return None;
        }
        let start = self.end - trimmed.len();
        // A comment always starts after the first non-white byte, which is not `;`.
        let end = self.comment.unwrap_or(self.end);
        Some((start, trim_end(&text[start..end])))
    }
}

/// The first `\n`, `=` or `;` at or after `from`. Eight bytes at a time: lines are mostly
/// letters, and testing a whole word for the three bytes takes a dozen operations.
fn next_landmark(bytes: &[u8], from: usize) -> Option<usize> {
    let mut at = from;
    while let Some(word) = bytes.get(at..at + 8) {
        let mut chunk = [0; 8];
        chunk.copy_from_slice(word);
        let found = landmarks(u64::from_le_bytes(chunk));
        if found != 0 {
            return Some(at + found.trailing_zeros() as usize / 8);
        }
        at += 8;
    }
    let tail = bytes.get(at..)?;
    let found = tail.iter().position(|b| matches!(b, b'\n' | b'=' | b';'));
    found.map(|n| at + n)
}

/// A mask whose lowest set bit is the high bit of the first `\n`, `=` or `;` byte of `word`
/// (little-endian); zero if there is none. Bits above the lowest may be false alarms.
fn landmarks(word: u64) -> u64 {
    const ONES: u64 = u64::from_le_bytes([0x01; 8]);
    const HIGHS: u64 = u64::from_le_bytes([0x80; 8]);
    // The classic test for a zero byte, applied to the word XOR each landmark repeated.
    let zero = |v: u64| v.wrapping_sub(ONES) & !v & HIGHS;
    zero(word ^ (ONES * u64::from(b'\n')))
        | zero(word ^ (ONES * u64::from(b'=')))
        | zero(word ^ (ONES * u64::from(b';')))
}

fn entry(file: FileId, line_start: usize, line: &str, eq: usize) -> Entry<'_> {
    let key = trim_end(&line[..eq]);
    let value_raw = &line[eq + 1..];
    // The line is trimmed already, so only the start of the value can hold white space.
    let value = trim_start(value_raw);
    let value_start = line_start + eq + 1 + (value_raw.len() - value.len());
    Entry {
        key,
        value,
        file,
        key_at: offset(line_start),
        value_at: offset(value_start),
    }
}

/// A byte offset as stored in an entry (`parse_ini` refuses texts whose offsets do not fit).
fn offset(at: usize) -> u32 {
    u32::try_from(at).unwrap_or(u32::MAX)
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
        let sections: Vec<_> = ini.sections().collect();
        assert_eq!(sections.len(), 1);
        assert_eq!(sections[0].entries.len(), 2);
        assert_eq!(d.len(), 4);
    }

    #[test]
    fn a_reopened_section_keeps_its_entries_together_and_in_file_order() {
        let mut d = Vec::new();
        let text = "[A]\nx=1\n[B]\ny=2\n[a]\nz=3\nX=4\n[C]\nx=5\n[D]\n";
        let ini = parse_ini(FileId(0), text, &mut d);
        let keys = |name: &str| -> Vec<&str> {
            let section = ini.section(name).unwrap();
            section.entries.iter().map(|e| e.key).collect()
        };
        assert_eq!(keys("a"), ["x", "z"]);
        assert_eq!(keys("b"), ["y"]);
        assert_eq!(keys("c"), ["x"], "a key of another section is no duplicate");
        assert!(keys("d").is_empty());
        let messages: Vec<_> = d.iter().map(|d| d.message.as_str()).collect();
        assert_eq!(
            messages,
            [
                "section `[a]` appears twice",
                "key appears twice in its section"
            ]
        );
    }

    #[test]
    fn landmarks_are_found_in_words_and_tails() {
        let text = b"abcdefgh;jk=lmnopqrstuvw\nxy";
        assert_eq!(next_landmark(text, 0), Some(8));
        assert_eq!(next_landmark(text, 9), Some(11));
        assert_eq!(next_landmark(text, 12), Some(24));
        assert_eq!(next_landmark(text, 25), None);
        assert_eq!(next_landmark(b"", 0), None);
        for at in 0..8 {
            let mut word = *b"........";
            word[at] = b'=';
            word[7] = b';';
            assert_eq!(
                landmarks(u64::from_le_bytes(word)).trailing_zeros() / 8,
                at as u32
            );
        }
    }

    #[test]
    fn bytes_are_counted_across_chunks() {
        let text = "[x]=".repeat(300);
        assert_eq!(count_brackets_and_equals(text.as_bytes()), (300, 300));
        assert_eq!(count_brackets_and_equals(b""), (0, 0));
    }
}
