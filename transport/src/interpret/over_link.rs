//! A run-time model's parameters read and written by name over any [`Link`]: the links, register
//! codecs, scale and checks generated code uses, chosen from the description at run time.

use core::fmt;
use std::string::String;
use std::vec;
use std::vec::Vec;

use super::registers;
use super::{parse, show, Described, InputError, Model, Shown};
use crate::error::BusError;
use crate::link::{Link, ReadRequest};
use crate::{OutsideBound, Protocol};

/// What is done to a parameter.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Access {
    /// Reading its value.
    Read,
    /// Writing a value.
    Write,
}

/// Where protocol `P` reaches a described parameter: the first of its addresses on `P` that
/// allows the access. A model's parameter implements it for each protocol it describes.
pub trait Addressed<P: Protocol> {
    /// The address for `access`, or `None` when the parameter has no such address on `P`.
    fn address(&self, access: Access) -> Option<P::Address>;
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
            InterpretError::Bus { parameter, cause } => write!(f, "{parameter}: {cause}"),
        }
    }
}

impl std::error::Error for InterpretError {}

/// The address of `parameter` on the link's protocol for `access`.
fn address_of<L: Link, P: Described + Addressed<L::Protocol>>(
    parameter: &P,
    access: Access,
) -> Result<<L::Protocol as Protocol>::Address, InterpretError> {
    parameter
        .address(access)
        .ok_or_else(|| InterpretError::NoAccess {
            parameter: parameter.name().into(),
            protocol: <L::Protocol as Protocol>::NAME,
            access,
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
pub fn read_raw<L, P>(link: &mut L, parameters: &[&P]) -> Result<Vec<Vec<u8>>, InterpretError>
where
    L: Link,
    P: Described + Addressed<L::Protocol>,
{
    let addresses = parameters
        .iter()
        .map(|p| address_of::<L, P>(*p, Access::Read))
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
/// the value the link puts on the wire (a signed value sign-extended into its registers).
pub fn write_raw<L, P>(link: &mut L, parameter: &P, bytes: &[u8]) -> Result<(), InterpretError>
where
    L: Link,
    P: Described + Addressed<L::Protocol>,
{
    let address = address_of::<L, P>(parameter, Access::Write)?;
    let wire = match link.wire_bytes(&address) {
        0 => bytes.to_vec(),
        width => registers::to_wire(parameter.data_type(), bytes, width),
    };
    link.write(&address, &wire)
        .map_err(|cause| bus_error(parameter, cause))
}

/// Reads the parameter called `name` and shows its value.
pub fn read<M, L>(model: &M, link: &mut L, name: &str) -> Result<Shown, InterpretError>
where
    M: Model,
    L: Link,
    M::Parameter: Addressed<L::Protocol>,
{
    let parameter = find(model, name)?;
    let raw = read_raw(link, &[parameter])?;
    Ok(show(model, parameter, &raw[0]))
}

/// Writes `text`, a value as a person types it (`1500rpm`, `velocity`, `raw:4950`), to the
/// parameter called `name`; returns the raw bytes written. A refused value sends nothing.
pub fn write<M, L>(
    model: &M,
    link: &mut L,
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
    check_bounds(model, link, parameter, &bytes)?;
    write_raw(link, parameter, &bytes)?;
    Ok(bytes)
}

/// Reads the parameters that bound `parameter` ([`Described::bounded_by`]) and refuses the raw
/// value `bytes` if it lies beyond one's current value, as generated `write_<name>` methods do.
pub fn check_bounds<M, L>(
    model: &M,
    link: &mut L,
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
        let current = read_raw(link, &[bound])?;
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
