//! `flags!`: the bit-set API of a generated bit-field word.
//!
//! A generated crate writes a flags word as plain items a reader can follow: the newtype, one
//! documented constant per named bit, and its multi-bit field accessors. This macro adds what
//! `bitflags` would have generated around them (the [`Flags`](bitflags::Flags) impl, the set
//! methods, operators, iteration and `Debug`), written once here instead of in every generated
//! crate. Every bit counts as known, as in a `bitflags!` type with `const _ = !0`: bits the
//! description does not name survive reads, `from_bits` and `!`.

use core::fmt;

/// For a newtype `struct $name($raw)` with one `pub const $flag: Self` per named bit: the
/// [`bitflags::Flags`] impl (names in the listed order), the inherent methods of a `bitflags!`
/// type (`empty`, `bits`, `contains`, `insert`, `iter_names`, ...), the bit operators, `Extend`,
/// `FromIterator`, `IntoIterator`, the hex, octal and binary formats, and a `Debug` that prints
/// the set flags' names (`DriveStatus(RUN | 0x100)`).
///
/// ```
/// #[derive(Clone, Copy, PartialEq, Eq, Hash)]
/// pub struct DriveStatus(u16);
/// impl DriveStatus {
///     pub const RUN: Self = Self(1 << 0);
///     pub const ALARM: Self = Self(1 << 4);
/// }
/// drivebus::flags!(DriveStatus: u16 = RUN, ALARM);
///
/// let status = DriveStatus::RUN | DriveStatus::from_bits_retain(0x100);
/// assert!(status.contains(DriveStatus::RUN) && !status.contains(DriveStatus::ALARM));
/// assert_eq!(format!("{status:?}"), "DriveStatus(RUN | 0x100)");
/// assert_eq!(status.iter_names().map(|(name, _)| name).collect::<Vec<_>>(), ["RUN"]);
/// assert_eq!((!DriveStatus::RUN).bits(), 0xfffe);
/// ```
#[doc(hidden)] // generated crates call it; users never need to
#[macro_export]
macro_rules! flags {
    ($name:ident: $raw:ty = $($flag:ident),* $(,)?) => {
        impl $crate::bitflags::Flags for $name {
            const FLAGS: &'static [$crate::bitflags::Flag<Self>] = &[
                $($crate::bitflags::Flag::new(stringify!($flag), Self::$flag),)*
                // Bits the description does not name still round-trip.
                $crate::bitflags::Flag::new("", Self(!0)),
            ];
            type Bits = $raw;
            fn bits(&self) -> $raw {
                self.0
            }
            fn from_bits_retain(bits: $raw) -> Self {
                Self(bits)
            }
        }

        $crate::flags!(@methods $name: $raw);
        $crate::flags!(@operators $name);
        $crate::flags!(@formats $name);
    };

    (@methods $name:ident: $raw:ty) => {
        impl $name {
            /// No bits set.
            #[inline]
            pub const fn empty() -> Self {
                Self(0)
            }
            /// Every bit set (unnamed bits count as known).
            #[inline]
            pub const fn all() -> Self {
                Self(!0)
            }
            /// The raw word.
            #[inline]
            pub const fn bits(&self) -> $raw {
                self.0
            }
            /// The word of `bits`; never `None`, since every bit is known.
            #[inline]
            pub const fn from_bits(bits: $raw) -> Option<Self> {
                Some(Self(bits))
            }
            /// The word of `bits` (nothing is truncated: every bit is known).
            #[inline]
            pub const fn from_bits_truncate(bits: $raw) -> Self {
                Self(bits)
            }
            /// The word of `bits`, unchanged.
            #[inline]
            pub const fn from_bits_retain(bits: $raw) -> Self {
                Self(bits)
            }
            /// The flag named `name` (its constant's name), if there is one.
            pub fn from_name(name: &str) -> Option<Self> {
                <Self as $crate::bitflags::Flags>::from_name(name)
            }
            /// Whether no bit is set.
            #[inline]
            pub const fn is_empty(&self) -> bool {
                self.0 == 0
            }
            /// Whether every bit is set.
            #[inline]
            pub const fn is_all(&self) -> bool {
                self.0 == !0
            }
            /// Whether any bit of `other` is set in `self`.
            #[inline]
            pub const fn intersects(&self, other: Self) -> bool {
                self.0 & other.0 != 0
            }
            /// Whether every bit of `other` is set in `self`.
            #[inline]
            pub const fn contains(&self, other: Self) -> bool {
                self.0 & other.0 == other.0
            }
            /// Sets the bits of `other`.
            #[inline]
            pub fn insert(&mut self, other: Self) {
                self.0 |= other.0;
            }
            /// Clears the bits of `other`.
            #[inline]
            pub fn remove(&mut self, other: Self) {
                self.0 &= !other.0;
            }
            /// Flips the bits of `other`.
            #[inline]
            pub fn toggle(&mut self, other: Self) {
                self.0 ^= other.0;
            }
            /// Sets (`value`) or clears the bits of `other`.
            #[inline]
            pub fn set(&mut self, other: Self, value: bool) {
                if value {
                    self.insert(other);
                } else {
                    self.remove(other);
                }
            }
            /// The bits set in both (`&`).
            #[inline]
            #[must_use]
            pub const fn intersection(self, other: Self) -> Self {
                Self(self.0 & other.0)
            }
            /// The bits set in either (`|`).
            #[inline]
            #[must_use]
            pub const fn union(self, other: Self) -> Self {
                Self(self.0 | other.0)
            }
            /// The bits of `self` not in `other` (`-`).
            #[inline]
            #[must_use]
            pub const fn difference(self, other: Self) -> Self {
                Self(self.0 & !other.0)
            }
            /// The bits set in exactly one (`^`).
            #[inline]
            #[must_use]
            pub const fn symmetric_difference(self, other: Self) -> Self {
                Self(self.0 ^ other.0)
            }
            /// Every bit flipped (`!`).
            #[inline]
            #[must_use]
            pub const fn complement(self) -> Self {
                Self(!self.0)
            }
            /// The set named flags, then the remaining bits as one value.
            #[inline]
            pub fn iter(&self) -> $crate::bitflags::iter::Iter<Self> {
                <Self as $crate::bitflags::Flags>::iter(self)
            }
            /// The set named flags with their names.
            #[inline]
            pub fn iter_names(&self) -> $crate::bitflags::iter::IterNames<Self> {
                <Self as $crate::bitflags::Flags>::iter_names(self)
            }
        }

        impl ::core::iter::IntoIterator for $name {
            type Item = Self;
            type IntoIter = $crate::bitflags::iter::Iter<Self>;
            fn into_iter(self) -> Self::IntoIter {
                self.iter()
            }
        }

        impl ::core::iter::Extend<$name> for $name {
            fn extend<T: ::core::iter::IntoIterator<Item = Self>>(&mut self, iterator: T) {
                for item in iterator {
                    self.insert(item);
                }
            }
        }

        impl ::core::iter::FromIterator<$name> for $name {
            fn from_iter<T: ::core::iter::IntoIterator<Item = Self>>(iterator: T) -> Self {
                let mut result = Self::empty();
                ::core::iter::Extend::extend(&mut result, iterator);
                result
            }
        }
    };

    (@operators $name:ident) => {
        $crate::flags!(@operator $name BitOr bitor BitOrAssign bitor_assign union);
        $crate::flags!(@operator $name BitAnd bitand BitAndAssign bitand_assign intersection);
        $crate::flags!(@operator $name BitXor bitxor BitXorAssign bitxor_assign symmetric_difference);
        $crate::flags!(@operator $name Sub sub SubAssign sub_assign difference);

        impl ::core::ops::Not for $name {
            type Output = Self;
            #[inline]
            fn not(self) -> Self {
                self.complement()
            }
        }
    };

    (@operator $name:ident $op:ident $op_fn:ident $assign:ident $assign_fn:ident $method:ident) => {
        impl ::core::ops::$op for $name {
            type Output = Self;
            #[inline]
            fn $op_fn(self, other: Self) -> Self {
                self.$method(other)
            }
        }

        impl ::core::ops::$assign for $name {
            #[inline]
            fn $assign_fn(&mut self, other: Self) {
                *self = self.$method(other);
            }
        }
    };

    (@formats $name:ident) => {
        impl ::core::fmt::Debug for $name {
            fn fmt(&self, f: &mut ::core::fmt::Formatter<'_>) -> ::core::fmt::Result {
                f.debug_tuple(stringify!($name))
                    .field(&$crate::flags_macro::Names(self))
                    .finish()
            }
        }

        $crate::flags!(@format $name Binary LowerHex UpperHex Octal);
    };

    (@format $name:ident $($format:ident)*) => {
        $(
            impl ::core::fmt::$format for $name {
                fn fmt(&self, f: &mut ::core::fmt::Formatter<'_>) -> ::core::fmt::Result {
                    ::core::fmt::$format::fmt(&self.0, f)
                }
            }
        )*
    };
}

/// The set flags of a word as `bitflags` prints them: `RUN | ALARM | 0x100`, or `0x0` when none is
/// set. Used by the `Debug` impl of [`flags!`](crate::flags).
#[doc(hidden)]
pub struct Names<'a, B>(pub &'a B);

impl<B> fmt::Debug for Names<'_, B>
where
    B: bitflags::Flags,
    B::Bits: bitflags::parser::WriteHex,
{
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.0.is_empty() {
            f.write_str("0x0")
        } else {
            bitflags::parser::to_writer(self.0, f)
        }
    }
}
