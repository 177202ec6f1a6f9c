//! The traits every generated parameter marker implements.
//!
//! A parameter is a zero-sized marker type. [`Parameter`] gives its identity and value codec;
//! [`Readable`] and [`Writable`] are implemented once per protocol the description allows the access
//! on. A missing implementation is a compile error that reads in plain English.

use crate::bound::Bound;
use crate::codec::Codec;
use crate::device::Device;
use crate::error::{Error, ValueError};
use crate::link::Link;
use crate::scale::Scale;
use crate::value::WireValue;
use crate::{Protocol, VariantId};

/// Identity and value codec of a parameter.
pub trait Parameter: 'static {
    /// Name as in the description.
    const NAME: &'static str;
    /// The fixed part of the scale; parameters with run-time factors override the protocol traits'
    /// scale functions instead.
    const SCALE: Scale = Scale::IDENTITY;
    /// The raw type on the wire.
    type Raw: WireValue;
    /// The engineering type users read and write (a unit newtype, enum, flags or the raw type).
    type Value;
    /// How raw and engineering values convert (see [`crate::codec`]).
    type Codec: Codec<Self::Raw, Self::Value>;

    /// Raw → engineering value.
    #[inline]
    fn decode(raw: Self::Raw, scale: Scale) -> Result<Self::Value, ValueError> {
        Self::Codec::decode(raw, scale)
    }
    /// Engineering → raw value; fails instead of rounding or truncating.
    #[inline]
    fn encode(value: Self::Value, scale: Scale) -> Result<Self::Raw, ValueError> {
        Self::Codec::encode(Self::NAME, value, scale)
    }
    /// Checks a raw value against the description's range and allowed values.
    fn check(_raw: &Self::Raw) -> Result<(), ValueError> {
        Ok(())
    }
    /// Whether writing `raw` stops, disables or quick-stops the drive (`stops` in the
    /// description): such a write is never refused before sending ([`crate::stop`]).
    fn stops(_raw: &Self::Raw) -> bool {
        false
    }
}

/// Where a parameter is reached on one protocol, per firmware or configuration variant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Placement<A: 'static> {
    /// The same address in every variant.
    Everywhere(A),
    /// The address in each variant, indexed by [`VariantId`]; `None` where the parameter is absent.
    PerVariant(&'static [Option<A>]),
}

impl<A: Copy> Placement<A> {
    /// The address in `variant`, or `None` if the parameter is absent there.
    #[inline]
    pub fn get(&self, variant: VariantId) -> Option<A> {
        match self {
            Placement::Everywhere(address) => Some(*address),
            Placement::PerVariant(table) => table.get(usize::from(variant.0)).copied().flatten(),
        }
    }
}

impl<A: Copy + PartialEq> Placement<A> {
    /// Whether the address depends on the variant: it differs between variants, or the
    /// parameter is absent from one. Such a parameter cannot be reached while the drive's
    /// variant is unknown.
    pub fn depends_on_variant(&self) -> bool {
        match self {
            Placement::Everywhere(_) => false,
            Placement::PerVariant(table) => {
                table.windows(2).any(|pair| pair[0] != pair[1]) || table.iter().any(Option::is_none)
            }
        }
    }
}

/// The parameter can be read over protocol `P`.
#[diagnostic::on_unimplemented(
    message = "the parameter `{Self}` cannot be read over {P}",
    label = "not readable over this protocol",
    note = "its description gives it no readable address for this protocol (write-only, or another protocol only)"
)]
pub trait Readable<P: Protocol>: Parameter {
    /// Where the parameter is read from.
    const READ_AT: Placement<P::Address>;
    /// The address to read from in the given variant, or `None` if absent there.
    #[inline]
    fn read_address(variant: VariantId) -> Option<P::Address> {
        Self::READ_AT.get(variant)
    }
    /// The scale in force; reads the factor's inputs for run-time scaled parameters.
    fn read_scale<L: Link<Protocol = P>>(_device: &mut Device<L>) -> Result<Scale, Error> {
        Ok(Self::SCALE)
    }
}

/// The parameter can be written over protocol `P`.
#[diagnostic::on_unimplemented(
    message = "the parameter `{Self}` cannot be written over {P}",
    label = "not writable over this protocol",
    note = "its description makes it read-only, or gives it no address for this protocol"
)]
pub trait Writable<P: Protocol>: Parameter {
    /// Where the parameter is written to.
    const WRITE_AT: Placement<P::Address>;
    /// The parameters whose current values bound this one (`bounds` in the description): every
    /// write reads them over the same link first and refuses a value beyond one with
    /// [`Error::OutsideBound`], sending nothing. A write that stops the drive is never refused
    /// ([`crate::stop`]) and reads none of them.
    const BOUNDS: &'static [BoundBy<P>] = &[];
    /// The address to write to in the given variant, or `None` if absent there.
    #[inline]
    fn write_address(variant: VariantId) -> Option<P::Address> {
        Self::WRITE_AT.get(variant)
    }
    /// The scale in force; reads the factor's inputs for run-time scaled parameters.
    fn write_scale<L: Link<Protocol = P>>(_device: &mut Device<L>) -> Result<Scale, Error> {
        Ok(Self::SCALE)
    }
}

/// Another parameter's raw integer value as a check reads it over protocol `P` before a write
/// (a bound) or on connect (an identity parameter): its name, where it is read and how its bytes
/// read as an integer. Built from the parameter's marker with [`RawInteger::of`].
#[derive(Debug, Clone, Copy)]
pub struct RawInteger<P: Protocol> {
    /// The parameter's name, as in the description.
    pub name: &'static str,
    /// Where it is read.
    pub read_at: Placement<P::Address>,
    /// Its raw type's decoding of the bytes read, as an integer.
    pub decode: fn(&[u8]) -> Result<i128, ValueError>,
}

impl<P: Protocol> RawInteger<P> {
    /// Parameter `B`, read over `P`.
    pub const fn of<B>() -> Self
    where
        B: Readable<P>,
        B::Raw: Into<i128>,
    {
        Self {
            name: B::NAME,
            read_at: B::READ_AT,
            decode: decode_integer::<B::Raw>,
        }
    }
}

fn decode_integer<R: WireValue + Into<i128>>(bytes: &[u8]) -> Result<i128, ValueError> {
    R::decode_le(bytes).map(Into::into)
}

/// A bound a parameter's writes over protocol `P` are checked against: the raw value written
/// must not lie beyond the current raw value of the parameter `by` ([`Bound::breached`]).
#[derive(Debug, Clone, Copy)]
pub struct BoundBy<P: Protocol> {
    /// How `by` bounds the parameter.
    pub bound: Bound,
    /// The bounding parameter.
    pub by: RawInteger<P>,
}

impl<P: Protocol> BoundBy<P> {
    /// The bound `bound` set by parameter `B`.
    pub const fn of<B>(bound: Bound) -> Self
    where
        B: Readable<P>,
        B::Raw: Into<i128>,
    {
        Self {
            bound,
            by: RawInteger::of::<B>(),
        }
    }
}

/// Proof that a raw value came off the wire; only `drivebus` can make one.
#[derive(Debug, Clone, Copy)]
pub struct FromWire(pub(crate) ());

/// Implemented by generated open enumerations: any raw value survives a read, but building one from
/// a number goes through the fallible `TryFrom`.
pub trait OpenEnum: Copy + 'static {
    /// The raw integer type.
    type Raw: Copy;
    /// Wraps any raw value, documented or not: what a read returns. Only `drivebus` holds the
    /// [`FromWire`] it takes, so users build values through the fallible `TryFrom`.
    fn from_raw(raw: Self::Raw, proof: FromWire) -> Self;
    /// The raw value.
    fn raw(self) -> Self::Raw;
    /// The name of the value in the description, or `None` if the drive sent an undocumented one.
    fn name(self) -> Option<&'static str>;
}

/// A value that can be written to parameter `P`: exactly its engineering type `P::Value`.
///
/// Generated code implements it once per parameter with an empty body (a blanket impl would turn
/// a wrong unit into an unreadable type-projection error); passing volts where rpm are expected then
/// reads as an error about the parameter.
#[diagnostic::on_unimplemented(
    message = "`{Self}` is not a value of the parameter `{P}`",
    label = "not the parameter's value type",
    note = "the value type of a parameter is its unit newtype, enum, flags or raw integer type; see its docs"
)]
pub trait ValueOf<P: Parameter>: Into<P::Value> {
    /// The value as the parameter's engineering type.
    #[inline]
    fn into_value(self) -> P::Value {
        self.into()
    }
}
