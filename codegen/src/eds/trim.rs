//! White space trimmed as `str::trim*` trims it, with a fast path for ASCII white space: EDS lines
//! and values are trimmed hundreds of thousands of times, nearly always of spaces, tabs and CRs.

/// `str::trim_start`.
pub fn trim_start(text: &str) -> &str {
    let ascii = text.trim_ascii_start();
    match ascii.as_bytes().first() {
        Some(&b) if beyond_ascii_fast_path(b) => ascii.trim_start(),
        _ => ascii,
    }
}

/// `str::trim_end`.
pub fn trim_end(text: &str) -> &str {
    let ascii = text.trim_ascii_end();
    match ascii.as_bytes().last() {
        Some(&b) if beyond_ascii_fast_path(b) => ascii.trim_end(),
        _ => ascii,
    }
}

/// `str::trim`.
pub fn trim(text: &str) -> &str {
    trim_end(trim_start(text))
}

/// Whether a byte left after ASCII trimming may still be white space to `char::is_whitespace`:
/// a byte of a multi-byte character, or the vertical tab (which `u8::is_ascii_whitespace` omits).
fn beyond_ascii_fast_path(byte: u8) -> bool {
    !byte.is_ascii() || byte == 0x0B
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn trims_like_str_trim() {
        for text in [
            "",
            " \t a b \r\n",
            "\u{0B}x\u{0B}",
            "\u{A0}\u{3000} x \u{2009}",
            "µ",
            " \u{0C}",
        ] {
            assert_eq!(trim_start(text), text.trim_start(), "{text:?}");
            assert_eq!(trim_end(text), text.trim_end(), "{text:?}");
            assert_eq!(trim(text), text.trim(), "{text:?}");
        }
    }
}
