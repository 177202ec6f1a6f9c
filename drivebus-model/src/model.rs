//! The device model the interpreter reads: what it needs to know of a described parameter, and
//! the names a description gives to raw values. `drivegen`'s IR implements both, so a description
//! loaded at run time is read and written through the same scale and checks as generated code.

use alloc::vec::Vec;

use crate::{Bound, DataType, Scale, Stops};
use crate::{Number, Protocol, Range};

/// A described parameter, as the interpreter sees it.
pub trait Described {
    /// The parameter's name (snake_case), for messages.
    fn name(&self) -> &str;
    /// The type of its raw value.
    fn data_type(&self) -> DataType;
    /// Its unit symbol, if it has one.
    fn unit(&self) -> Option<&str>;
    /// Its fixed scale ([`Scale::IDENTITY`] when unscaled); `None` when the scale is computed at
    /// run time from other parameters, so only raw values can be converted.
    fn fixed_scale(&self) -> Option<Scale>;
    /// Its raw range, if described.
    fn range(&self) -> Option<&Range>;
    /// Its allowed raw values (empty: any value in range).
    fn allowed(&self) -> &[Number];
    /// The parameters whose current values bound it (none by default).
    fn bounded_by(&self) -> BoundedBy<'_> {
        BoundedBy::default()
    }
    /// The writes of it that stop the drive, never refused before sending (none by default).
    fn stops(&self) -> Stops<'_> {
        Stops::Never
    }
}

/// The parameters whose current raw values bound a parameter: it lies within `min ..= max` and
/// within ± `magnitude`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct BoundedBy<'a> {
    /// The parameter whose value is the least allowed value.
    pub min: Option<&'a str>,
    /// The parameter whose value is the greatest allowed value.
    pub max: Option<&'a str>,
    /// The parameter whose value `v` bounds it to `-v ..= v`.
    pub magnitude: Option<&'a str>,
}

impl<'a> BoundedBy<'a> {
    /// Each bounding parameter with how it bounds.
    pub fn each(&self) -> impl Iterator<Item = (Bound, &'a str)> {
        [
            (Bound::Min, self.min),
            (Bound::Max, self.max),
            (Bound::Magnitude, self.magnitude),
        ]
        .into_iter()
        .filter_map(|(bound, name)| Some((bound, name?)))
    }
}

/// A device model loaded at run time: parameters by name and the names of their raw values.
pub trait Model {
    /// The model's parameter type.
    type Parameter: Described;
    /// The parameter called `name`.
    fn parameter(&self, name: &str) -> Option<&Self::Parameter>;
    /// The enumeration or bit field that names the raw values of `parameter`.
    fn symbols<'a>(&'a self, parameter: &'a Self::Parameter) -> Symbols<'a>;
}

/// How a description names the raw values of a parameter.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Symbols<'a> {
    /// Plain numbers, not named.
    Plain,
    /// An enumeration: its name and its `(name, value)` pairs.
    Enum {
        /// The enumeration's name.
        name: &'a str,
        /// Its values.
        values: Vec<(&'a str, i64)>,
    },
    /// A bit field: its name and its `(name, bit)` pairs, bit 0 the least significant.
    Flags {
        /// The bit field's name.
        name: &'a str,
        /// Its bits.
        bits: Vec<(&'a str, u32)>,
    },
}

/// What is done to a parameter.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Access {
    /// Reading its value.
    Read,
    /// Writing a value.
    Write,
}

/// Where protocol `P` reaches a described parameter. A model's parameter implements it for each
/// protocol it describes.
pub trait Addressed<P: Protocol> {
    /// The address for `access` in the variant called `variant`; with `None` (the drive's
    /// variant is not known) only an address that is the same in every variant.
    fn address(&self, access: Access, variant: Option<&str>) -> Result<P::Address, Unreachable>;
}

/// Why a parameter has no address for an access.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unreachable {
    /// It has no address on the protocol that allows the access.
    NoAccess,
    /// It does not exist in the variant.
    NotInVariant,
    /// Its address depends on the variant, which is not known.
    DependsOnVariant,
}
