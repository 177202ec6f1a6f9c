//! Short texts kept without a heap allocation: an EDS has thousands of values like `0x1000`,
//! `rw` or `$NODEID+0x180`, and allocating each one dominated reading large files.

use std::borrow::Borrow;
use std::fmt;
use std::hash::{Hash, Hasher};
use std::ops::Deref;

/// Bytes stored inline; longer texts go to the heap.
const INLINE: usize = 30;

/// An immutable string, inline up to 30 bytes.
#[derive(Clone)]
pub enum ShortText {
    /// Up to 30 bytes of UTF-8 (`INLINE`) and their length.
    Inline([u8; INLINE], u8),
    /// A longer text.
    Heap(Box<str>),
}

impl From<&str> for ShortText {
    fn from(text: &str) -> Self {
        if text.len() <= INLINE {
            let mut bytes = [0; INLINE];
            bytes[..text.len()].copy_from_slice(text.as_bytes());
            ShortText::Inline(bytes, text.len() as u8)
        } else {
            ShortText::Heap(text.into())
        }
    }
}

impl ShortText {
    /// `text` in ASCII lower case.
    pub fn lowercase(text: &str) -> Self {
        let mut short = Self::from(text);
        match &mut short {
            ShortText::Inline(bytes, len) => bytes[..usize::from(*len)].make_ascii_lowercase(),
            ShortText::Heap(text) => text.make_ascii_lowercase(),
        }
        short
    }
}

impl Deref for ShortText {
    type Target = str;

    fn deref(&self) -> &str {
        match self {
            // The bytes were copied from a `&str` whole, so they are valid UTF-8.
            ShortText::Inline(bytes, len) => {
                std::str::from_utf8(&bytes[..usize::from(*len)]).unwrap_or_default()
            }
            ShortText::Heap(text) => text,
        }
    }
}

// Equal and hashed as its text, so that maps keyed by it can be searched with a `&str`.
impl PartialEq for ShortText {
    fn eq(&self, other: &Self) -> bool {
        **self == **other
    }
}

impl Eq for ShortText {}

impl Hash for ShortText {
    fn hash<H: Hasher>(&self, state: &mut H) {
        (**self).hash(state)
    }
}

impl Borrow<str> for ShortText {
    fn borrow(&self) -> &str {
        self
    }
}

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
        assert_eq!(&*ShortText::from("µ".repeat(15).as_str()), "µ".repeat(15));
        assert_eq!(&*ShortText::from(long), long);
        assert!(matches!(
            ShortText::from("$NODEID+0x180"),
            ShortText::Inline(..)
        ));
        assert_eq!(&*ShortText::lowercase("1A00Sub1"), "1a00sub1");
        assert_eq!(
            &*ShortText::lowercase(&long.to_uppercase()),
            long.to_uppercase().to_ascii_lowercase()
        );
    }
}
