//! Bytes of an EDS file to text: UTF-8, with a byte-order mark or Windows-1252 bytes tolerated.
//!
//! Vendor tools write EDS files on Windows; `°` and `µ` in names often arrive as cp1252 bytes.

/// How the bytes had to be read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Encoding {
    /// Plain UTF-8.
    Utf8,
    /// UTF-8 after a byte-order mark (which CANopen tools refuse).
    Utf8WithBom,
    /// Not UTF-8: read as Windows-1252.
    Cp1252,
}

/// Characters of the Windows-1252 bytes 0x80..=0x9F (undefined bytes map to U+FFFD).
const CP1252_HIGH: [char; 32] = [
    '€', '\u{FFFD}', '‚', 'ƒ', '„', '…', '†', '‡', 'ˆ', '‰', 'Š', '‹', 'Œ', '\u{FFFD}', 'Ž',
    '\u{FFFD}', '\u{FFFD}', '‘', '’', '“', '”', '•', '–', '—', '˜', '™', 'š', '›', 'œ', '\u{FFFD}',
    'ž', 'Ÿ',
];

/// Decodes `bytes`, saying which encoding was used.
pub fn decode(bytes: &[u8]) -> (String, Encoding) {
    if let Some(rest) = bytes.strip_prefix(b"\xEF\xBB\xBF") {
        if let Ok(text) = std::str::from_utf8(rest) {
            return (text.to_owned(), Encoding::Utf8WithBom);
        }
    }
    match std::str::from_utf8(bytes) {
        Ok(text) => (text.to_owned(), Encoding::Utf8),
        Err(_) => (bytes.iter().map(|&b| cp1252(b)).collect(), Encoding::Cp1252),
    }
}

fn cp1252(byte: u8) -> char {
    match byte {
        0x80..=0x9F => CP1252_HIGH[usize::from(byte - 0x80)],
        other => char::from(other),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bom_is_stripped_and_cp1252_is_decoded() {
        assert_eq!(
            decode(b"\xEF\xBB\xBF[A]"),
            ("[A]".into(), Encoding::Utf8WithBom)
        );
        assert_eq!(
            decode(b"t=25\xB0C \x80"),
            ("t=25°C €".into(), Encoding::Cp1252)
        );
        assert_eq!(decode("µ".as_bytes()), ("µ".into(), Encoding::Utf8));
    }
}
