//! A run-time model's parameters read and written by name over any [`Link`]: the links, register
//! codecs, scale and checks generated code uses, chosen from the description at run time.

use core::fmt;
use std::string::String;
use std::vec;
use std::vec::Vec;

use super::registers;
use super::{parse, show, Access, Addressed, Described, InputError, Model, Shown, Unreachable};
use crate::error::BusError;
use crate::link::{Link, ReadRequest};
use crate::{OutsideBound, Protocol};

/// What a session knows of the variant (firmware or configuration) of the drive it talks to,
/// as the generated handle's `detect_variant` learns it: read from the description's
/// `selected_by` parameter when the session opens, or given by the user.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Variant {
    /// The description has no variants.
    Single,
    /// The drive is in this variant.
    Selected(String),
    /// Not known: `selector` held `found`, which selects no variant, or could not be read
    /// (`None`). Parameters whose address depends on the variant are not reached, and nothing
    /// but a stop is written.
    Unknown {
        /// The parameter that selects the variant.
        selector: String,
        /// The raw value it held.
        found: Option<i128>,
    },
}

impl Variant {
    /// The selected variant's name, if one is selected.
    pub fn selected(&self) -> Option<&str> {
        match self {
            Variant::Selected(name) => Some(name),
            _ => None,
        }
    }
}

/// Why a parameter could not be read or written; nothing further was sent.
#[derive(Debug, Clone, PartialEq)]
pub enum InterpretError {
    /// The model has no parameter of that name.
    UnknownParameter(String),
    /// The parameter cannot be read (or written) over the link's protocol.
    NoAccess {
        /// The parameter.
        parameter: String,
        /// The link's protocol.
        protocol: &'static str,
        /// What was wanted.
        access: Access,
    },
    /// The value typed was refused before anything was sent.
    Input {
        /// The parameter.
        parameter: String,
        /// Why.
        cause: InputError,
    },
    /// The value lies beyond the current value of a parameter that bounds it; nothing was
    /// written.
    OutsideBound(OutsideBound<String>),
    /// The parameter does not exist in the drive's variant.
    NotInVariant {
        /// The parameter.
        parameter: String,
        /// The variant.
        variant: String,
    },
    /// The drive's variant is not known and the parameter's address depends on it, or the write
    /// is not a stop: nothing was sent.
    VariantUnknown {
        /// The parameter.
        parameter: String,
        /// The parameter that selects the variant.
        selector: String,
        /// The raw value it held, when it could be read.
        found: Option<i128>,
    },
    /// The bus failed, or the drive refused or answered a value outside the parameter's type.
    Bus {
        /// The parameter.
        parameter: String,
        /// Why.
        cause: BusError,
    },
}

impl fmt::Display for InterpretError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            InterpretError::UnknownParameter(name) => write!(f, "no parameter `{name}`"),
            InterpretError::NoAccess {
                parameter,
                protocol,
                access,
            } => {
                let (verb, what) = match access {
                    Access::Read => ("read", "write-only"),
                    Access::Write => ("written", "read-only"),
                };
                write!(
                    f,
                    "{parameter} cannot be {verb} over {protocol} (it is {what} there, or has no {protocol} address)"
                )
            }
            InterpretError::Input { parameter, cause } => write!(f, "{parameter}: {cause}"),
            InterpretError::OutsideBound(refusal) => write!(f, "{refusal}"),
            InterpretError::NotInVariant { parameter, variant } => {
                write!(f, "{parameter} does not exist in variant {variant}")
            }
            InterpretError::VariantUnknown {
                parameter,
                selector,
                found,
            } => {
                write!(f, "{parameter} not reached: ")?;
                match found {
                    Some(found) => write!(
                        f,
                        "{selector} = {found} selects no variant of the description"
                    )?,
                    None => write!(
                        f,
                        "the drive's variant is not known ({selector} could not be read)"
                    )?,
                }
                write!(
                    f,
                    ", and nothing is guessed: name the variant (drivegen: --variant)"
                )
            }
            InterpretError::Bus { parameter, cause } => write!(f, "{parameter}: {cause}"),
        }
    }
}

impl std::error::Error for InterpretError {}

/// The address of `parameter` on the link's protocol for `access` in `variant`.
fn address_of<L: Link, P: Described + Addressed<L::Protocol>>(
    parameter: &P,
    access: Access,
    variant: &Variant,
) -> Result<<L::Protocol as Protocol>::Address, InterpretError> {
    parameter
        .address(access, variant.selected())
        .map_err(|why| match (why, variant) {
            (Unreachable::NoAccess, _) => InterpretError::NoAccess {
                parameter: parameter.name().into(),
                protocol: <L::Protocol as Protocol>::NAME,
                access,
            },
            (_, Variant::Unknown { selector, found }) => InterpretError::VariantUnknown {
                parameter: parameter.name().into(),
                selector: selector.clone(),
                found: *found,
            },
            (_, variant) => InterpretError::NotInVariant {
                parameter: parameter.name().into(),
                variant: variant.selected().unwrap_or("of the description").into(),
            },
        })
}

fn bus_error(parameter: &impl Described, cause: BusError) -> InterpretError {
    InterpretError::Bus {
        parameter: parameter.name().into(),
        cause,
    }
}

/// Reads the raw value (little-endian bytes of its type) of each parameter, in one
/// [`Link::read_many`]: over Modbus the fewest requests the link's limits allow. A failure names
/// the parameter whose read failed ([`Link::failed_request`]).
pub fn read_raw<L, P>(
    link: &mut L,
    variant: &Variant,
    parameters: &[&P],
) -> Result<Vec<Vec<u8>>, InterpretError>
where
    L: Link,
    P: Described + Addressed<L::Protocol>,
{
    let addresses = parameters
        .iter()
        .map(|p| address_of::<L, P>(*p, Access::Read, variant))
        .collect::<Result<Vec<_>, _>>()?;
    // Room for the wire value, the type, and any expedited SDO answer.
    let mut wire: Vec<Vec<u8>> = parameters
        .iter()
        .zip(&addresses)
        .map(|(p, a)| vec![0; link.wire_bytes(a).max(p.data_type().bytes().into()).max(8)])
        .collect();
    let mut requests: Vec<ReadRequest<'_, _>> = addresses
        .iter()
        .zip(&mut wire)
        .map(|(address, buf)| ReadRequest {
            address: *address,
            buf,
            len: 0,
        })
        .collect();
    if let Err(cause) = link.read_many(&mut requests) {
        let failed = link.failed_request(&requests).unwrap_or(0);
        return Err(bus_error(parameters[failed], cause));
    }
    let lengths: Vec<usize> = requests.iter().map(|r| r.len).collect();
    parameters
        .iter()
        .zip(wire)
        .zip(lengths)
        .map(|((parameter, mut wire), len)| {
            wire.truncate(len);
            registers::from_wire(parameter.data_type(), wire)
                .map_err(|unfit| bus_error(*parameter, BusError::Frame(unfit.reason())))
        })
        .collect()
}

/// Writes the raw value `bytes` (little-endian, the parameter's type) of `parameter`, widened to
/// the value the link puts on the wire (a signed value sign-extended into its registers). While
/// the drive's variant is unknown nothing is written but a stop ([`crate::stop`]).
pub fn write_raw<L, P>(
    link: &mut L,
    variant: &Variant,
    parameter: &P,
    bytes: &[u8],
) -> Result<(), InterpretError>
where
    L: Link,
    P: Described + Addressed<L::Protocol>,
{
    refuse_unless_stop(variant, parameter, bytes)?;
    let address = address_of::<L, P>(parameter, Access::Write, variant)?;
    let wire = match link.wire_bytes(&address) {
        0 => bytes.to_vec(),
        width => registers::to_wire(parameter.data_type(), bytes, width),
    };
    link.write(&address, &wire)
        .map_err(|cause| bus_error(parameter, cause))
}

/// Refuses a write while the drive's variant is unknown, unless it stops the drive.
fn refuse_unless_stop<P: Described>(
    variant: &Variant,
    parameter: &P,
    bytes: &[u8],
) -> Result<(), InterpretError> {
    let refusal = match variant {
        Variant::Unknown { selector, found } => Some(InterpretError::VariantUnknown {
            parameter: parameter.name().into(),
            selector: selector.clone(),
            found: *found,
        }),
        Variant::Single | Variant::Selected(_) => None,
    };
    waive_for_stop(parameter, bytes, refusal).map_or(Ok(()), Err)
}

/// The one checked write of the interpreter: refused while the variant is unknown (unless it
/// stops the drive), then checked against the parameters that bound it, then written.
pub fn write_checked<M, L>(
    model: &M,
    link: &mut L,
    variant: &Variant,
    parameter: &M::Parameter,
    bytes: &[u8],
) -> Result<(), InterpretError>
where
    M: Model,
    L: Link,
    M::Parameter: Addressed<L::Protocol>,
{
    refuse_unless_stop(variant, parameter, bytes)?;
    check_bounds(model, link, variant, parameter, bytes)?;
    write_raw(link, variant, parameter, bytes)
}

/// `refusal`, unless writing `bytes` to `parameter` stops the drive: a stop is never refused
/// client-side ([`crate::Stops::waive`]).
pub fn waive_for_stop<P: Described, R>(
    parameter: &P,
    bytes: &[u8],
    refusal: Option<R>,
) -> Option<R> {
    match super::raw::to_int(parameter.data_type(), bytes) {
        Some(raw) => parameter.stops().waive(raw, refusal),
        None => refusal,
    }
}

/// Reads the parameter called `name` and shows its value.
pub fn read<M, L>(
    model: &M,
    link: &mut L,
    variant: &Variant,
    name: &str,
) -> Result<Shown, InterpretError>
where
    M: Model,
    L: Link,
    M::Parameter: Addressed<L::Protocol>,
{
    let parameter = find(model, name)?;
    let raw = read_raw(link, variant, &[parameter])?;
    Ok(show(model, parameter, &raw[0]))
}

/// Writes `text`, a value as a person types it (`1500rpm`, `velocity`, `raw:4950`), to the
/// parameter called `name`; returns the raw bytes written. A refused value sends nothing.
pub fn write<M, L>(
    model: &M,
    link: &mut L,
    variant: &Variant,
    name: &str,
    text: &str,
) -> Result<Vec<u8>, InterpretError>
where
    M: Model,
    L: Link,
    M::Parameter: Addressed<L::Protocol>,
{
    let parameter = find(model, name)?;
    let bytes = parse(model, parameter, text).map_err(|cause| InterpretError::Input {
        parameter: name.into(),
        cause,
    })?;
    write_checked(model, link, variant, parameter, &bytes)?;
    Ok(bytes)
}

/// Reads the parameters that bound `parameter` ([`Described::bounded_by`]) and refuses the raw
/// value `bytes` if it lies beyond one's current value, as a generated handle's writes do.
pub fn check_bounds<M, L>(
    model: &M,
    link: &mut L,
    variant: &Variant,
    parameter: &M::Parameter,
    bytes: &[u8],
) -> Result<(), InterpretError>
where
    M: Model,
    L: Link,
    M::Parameter: Addressed<L::Protocol>,
{
    let Some(raw) = super::raw::to_int(parameter.data_type(), bytes) else {
        return Ok(());
    };
    for (kind, name) in parameter.bounded_by().each() {
        let bound = find(model, name)?;
        let current = read_raw(link, variant, &[bound])?;
        let limit = super::raw::to_int(bound.data_type(), &current[0]).unwrap_or_default();
        if kind.breached(raw, limit) {
            return Err(InterpretError::OutsideBound(OutsideBound {
                parameter: parameter.name().into(),
                bound: name.into(),
                raw,
                limit,
            }));
        }
    }
    Ok(())
}

fn find<'m, M: Model>(model: &'m M, name: &str) -> Result<&'m M::Parameter, InterpretError> {
    model
        .parameter(name)
        .ok_or_else(|| InterpretError::UnknownParameter(name.into()))
}
