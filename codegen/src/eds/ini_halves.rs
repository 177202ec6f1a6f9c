//! The INI pass of a large file on two threads: the text is cut at a section header near its
//! middle, both halves are read at once, and the second is appended to the first.
//!
//! A half needs nothing from the other, except to know whether one of its sections repeats a
//! section of the other half: that is rare, and then the file is read again in one pass, so that
//! the warnings come out exactly as that pass gives them.

use super::parse::{is_header_line, read_lines, Ini};
use super::threads;
use crate::diagnostic::{Diagnostic, FileId};

/// The sections of `text` (whose offsets fit `u32`) read in two halves, their diagnostics pushed
/// in file order; `None` (nothing pushed) when the text has no header to cut at, a section
/// repeats across the halves or no thread could be started.
pub(super) fn parse<'t>(
    file: FileId,
    text: &'t str,
    diagnostics: &mut Vec<Diagnostic>,
) -> Option<Ini<'t>> {
    let cut = cut(text)?;
    let mut later = Vec::new();
    let first_half = || {
        let mut earlier = Vec::new();
        let (ini, lines) = read_lines(file, text, 0..cut, &mut earlier);
        (ini, lines, earlier)
    };
    let second_half = || read_lines(file, text, cut..text.len(), &mut later).0;
    let ((mut ini, lines, earlier), second) = threads::join(first_half, second_half)?;
    ini.append(second, lines).ok()?;
    diagnostics.extend(earlier);
    diagnostics.extend(later);
    Some(ini)
}

/// Where the first header line after the middle of `text` starts (a line starting with `[`).
fn cut(text: &str) -> Option<usize> {
    let bytes = text.as_bytes();
    let mut at = text.len() / 2;
    while let Some(newline) = bytes.get(at..)?.iter().position(|&b| b == b'\n') {
        at += newline + 1;
        if bytes.get(at) == Some(&b'[') && is_header_line(text, at) {
            return Some(at);
        }
    }
    None
}
