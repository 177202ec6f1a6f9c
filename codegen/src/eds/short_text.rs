//! Short texts kept without a heap allocation: an EDS has thousands of values like `0x1000`,
//! `rw` or `$NODEID+0x180`, and allocating each one dominated reading large files.

use std::fmt;
use std::ops::Deref;

/// Bytes stored inline; longer texts go to the heap. 22 keeps a `ShortText` at 24 bytes (a `String`'s
/// size) and still holds values like `$NODEID+0x180` or `0x7FFFFFFF`.
const INLINE: usize = 22;

/// An immutable string, inline up to 22 bytes.
#[derive(Clone)]
pub struct ShortText(Repr);

/// Private, so that only [`ShortText::from`] makes inline bytes:
/// they are always valid UTF-8, which [`ShortText`]'s `Deref` relies on.
#[derive(Clone)]
enum Repr {
    /// Up to 22 bytes of UTF-8 (`INLINE`) and their length.
    Inline([u8; INLINE], u8),
    /// A longer text.
    Heap(Box<str>),
}

impl From<&str> for ShortText {
    fn from(text: &str) -> Self {
        if text.len() > INLINE {
            return ShortText(Repr::Heap(text.into()));
        }
        // Zeroed in place, then filled: copying into a separate array and moving that (wide
        // loads of bytes just stored narrowly) stalled on store forwarding.
        let mut short = ShortText(Repr::Inline([0; INLINE], text.len() as u8));
        if let Repr::Inline(bytes, _) = &mut short.0 {
            bytes[..text.len()].copy_from_slice(text.as_bytes());
        }
        short
    }
}

impl Deref for ShortText {
    type Target = str;

    fn deref(&self) -> &str {
        match &self.0 {
            Repr::Inline(bytes, len) => {
                let bytes = &bytes[..usize::from(*len)];
                // SAFETY: inline bytes are only written by `from`, a copy of a whole `&str`, so
                // they are valid UTF-8; the representation is private, so nothing else can write
                // them. Checking again on
                // every read cost more than copying the text (tens of thousands of reads per
                // EDS).
                unsafe { std::str::from_utf8_unchecked(bytes) }
            }
            Repr::Heap(text) => text,
        }
    }
}

// Equal as its text.
impl PartialEq for ShortText {
    fn eq(&self, other: &Self) -> bool {
        **self == **other
    }
}

impl Eq for ShortText {}

impl fmt::Debug for ShortText {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(&**self, f)
    }
}

impl fmt::Display for ShortText {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn short_and_long_texts_read_back() {
        let long = "a name longer than thirty bytes, with µ";
        assert_eq!(&*ShortText::from("rw"), "rw");
        assert_eq!(&*ShortText::from(""), "");
        assert_eq!(&*ShortText::from("µ".repeat(11).as_str()), "µ".repeat(11));
        assert_eq!(std::mem::size_of::<ShortText>(), 24);
        assert_eq!(&*ShortText::from(long), long);
        let inline = |text: &str| matches!(ShortText::from(text).0, Repr::Inline(..));
        assert!(inline("$NODEID+0x180"));
        assert!(!inline(long));
    }
}
