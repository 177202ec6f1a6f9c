//! `open_enum!`: the impls every generated open enumeration shares.
//!
//! A generated enumeration declares its newtype, one constant per documented value and its
//! `name()` lookup; this macro adds the rest, written once here instead of in every generated crate.

/// For a newtype `struct $name($raw)` with an inherent `const fn name(self) -> Option<&'static str>`:
/// `raw()`, `is_known()`, a crate-private `from_raw`, the fallible `TryFrom<$raw>` (documented values
/// only), a `Debug` that prints the value's name, and [`OpenEnum`](crate::parameter::OpenEnum).
///
/// ```
/// #[derive(Clone, Copy, PartialEq, Eq)]
/// pub struct BaudRate(u16);
/// impl BaudRate {
///     pub const B9600: Self = Self(96);
///     pub const fn name(self) -> Option<&'static str> {
///         match self.0 {
///             96 => Some("b9600"),
///             _ => None,
///         }
///     }
/// }
/// drivebus::open_enum!(BaudRate: u16);
///
/// assert_eq!(BaudRate::try_from(96), Ok(BaudRate::B9600));
/// assert!(BaudRate::try_from(97).is_err());
/// assert_eq!(format!("{:?}", BaudRate::B9600), "b9600");
/// ```
#[doc(hidden)] // generated crates call it; users never need to
#[macro_export]
macro_rules! open_enum {
    ($name:ident: $raw:ty) => {
        impl $name {
            /// Wraps any raw value; only reads use this, users go through `TryFrom`.
            #[allow(dead_code)]
            pub(crate) const fn from_raw(raw: $raw) -> Self {
                Self(raw)
            }
            /// The raw value.
            pub const fn raw(self) -> $raw {
                self.0
            }
            /// Whether the description documents this value.
            pub const fn is_known(self) -> bool {
                self.name().is_some()
            }
        }

        impl ::core::convert::TryFrom<$raw> for $name {
            type Error = $crate::ValueError;
            fn try_from(raw: $raw) -> Result<Self, Self::Error> {
                let value = Self(raw);
                if value.is_known() {
                    Ok(value)
                } else {
                    Err($crate::ValueError::NotAllowed {
                        parameter: stringify!($name),
                        raw: $crate::interpret::RawValue::Int(raw as i128),
                    })
                }
            }
        }

        impl ::core::fmt::Debug for $name {
            fn fmt(&self, f: &mut ::core::fmt::Formatter<'_>) -> ::core::fmt::Result {
                match self.name() {
                    Some(name) => f.write_str(name),
                    None => write!(f, "{}({})", stringify!($name), self.0),
                }
            }
        }

        impl $crate::parameter::OpenEnum for $name {
            type Raw = $raw;
            fn from_raw(raw: $raw, _: $crate::parameter::FromWire) -> Self {
                Self(raw)
            }
            fn raw(self) -> $raw {
                self.0
            }
            fn name(self) -> Option<&'static str> {
                $name::name(self)
            }
        }
    };
}
