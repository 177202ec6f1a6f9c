//! The one deliberate way to change safety-function parameters (the CiA 402-4 objects of a safety
//! drive: command mappings, STO, SBC, SLS, SLSa, SDI, SMS): in NMT Pre-Operational only, write the
//! values, read back every object the function's signature covers, and write the recomputed
//! signature — the rules of the SWD manual: signatures are updated in Pre-Operational, and a
//! signature that does not match sets 6607h to 00h (lines 3484, 3570); each function's signature
//! is a CRC-16-CCITT with start value 0 over the listed objects in order (lines 3497-3562,
//! 3633-3860).
//!
//! Generated drive crates give a parameter marked `safety = true` no setter; it implements
//! [`SafetyFunctionParameter`] instead, and [`SafetyValue::of`] is the only way to turn a value
//! of it into a write. A write of an object the chosen signature does not cover is refused before
//! any frame is sent ([`SafetyWriteError::NotSigned`]): it would change the function without
//! updating a signature.
//!
//! **Unverified.** The manual gives no test vector for any safety-function signature, and they
//! sign objects whose values it never gives (6600h-6603h): what is implemented is what the
//! tables state — each object's little-endian bytes at the listed width, in the listed order,
//! objects the tables call non-existent as zeros.

use super::safety_write::SafetyWriteError;
use super::signature::SIGNATURE_CRC;
use crate::canopen::address::{NodeId, ObjectAddress};
use crate::canopen::link::SdoBus;
use crate::canopen::nmt::NmtState;
use crate::canopen::pdo::SdoWrite;
use crate::canopen::CanOpen;
use crate::device::{named, Device};
use crate::error::{Error, ValueError};
use crate::link::Link;
use crate::parameter::{Readable, ValueOf};
use crate::value::WireValue;

/// A safety-function parameter: readable, never plainly writable, written only through
/// [`write_safety_function`]. Implemented by generated code for parameters marked `safety = true`.
#[diagnostic::on_unimplemented(
    message = "`{Self}` is not a safety-function parameter",
    label = "not written through the safety-function write",
    note = "only parameters a description marks `safety = true` go through `write_safety_function`; write other parameters with their setter"
)]
pub trait SafetyFunctionParameter: Readable<CanOpen> {
    /// The object the safety-function write writes.
    const OBJECT: ObjectAddress;
}

/// One entry of a safety-function signature table, in table order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Signed {
    /// Sub-indices `first..=last` of `index`, `bytes` each ("4 bytes for each sub-index").
    Each {
        /// Object index.
        index: u16,
        /// First sub-index.
        first: u8,
        /// Last sub-index.
        last: u8,
        /// Bytes signed per sub-index.
        bytes: u8,
    },
    /// The sub-index of `index` numbered as the function ("6691h 01 to 08, 2 bytes" in the
    /// signature of SLS x: sub-index x).
    OfFunction {
        /// Object index.
        index: u16,
        /// Bytes signed.
        bytes: u8,
    },
    /// One sub-index.
    One {
        /// Object index.
        index: u16,
        /// Sub-index.
        subindex: u8,
        /// Bytes signed.
        bytes: u8,
    },
    /// An object the table says does not exist: `bytes` zeros are signed.
    Absent {
        /// Bytes signed.
        bytes: u8,
    },
}

impl Signed {
    /// Whether this entry signs `index`:`subindex` in the signature of function `function`.
    fn covers(&self, function: u8, index: u16, subindex: u8) -> bool {
        match *self {
            Self::Each {
                index: i,
                first,
                last,
                ..
            } => i == index && (first..=last).contains(&subindex),
            Self::OfFunction { index: i, .. } => i == index && subindex == function,
            Self::One {
                index: i,
                subindex: s,
                ..
            } => i == index && s == subindex,
            Self::Absent { .. } => false,
        }
    }
}

/// A safety function's signature: where it is stored and what it signs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FunctionSignature {
    /// The function's name, for messages (`"SLS"`).
    pub name: &'static str,
    /// The object the signatures are stored in.
    pub index: u16,
    /// How many instances the function has (SLS: 8, one signature each at sub-index 1..=8); 0
    /// for a function with one signature at sub-index 0.
    pub instances: u8,
    /// What the signature covers, in order.
    pub signed: &'static [Signed],
}

impl FunctionSignature {
    /// The sub-index of instance `function`'s signature, if the function has that instance.
    fn stored_at(&self, function: u8) -> Option<u8> {
        match self.instances {
            0 => (function == 0).then_some(0),
            n => (1..=n).contains(&function).then_some(function),
        }
    }

    /// Whether the signature of instance `function` covers `index`:`subindex`.
    pub fn covers(&self, function: u8, index: u16, subindex: u8) -> bool {
        self.signed
            .iter()
            .any(|s| s.covers(function, index, subindex))
    }
}

/// A value of a safety-function parameter, range-checked and encoded for its object: what
/// [`write_safety_function`] writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SafetyValue {
    write: SdoWrite,
}

impl SafetyValue {
    /// `value` of parameter `P`, scaled as `device` scales it (run-time factors are read from
    /// it) and checked against the description's range. Nothing is written.
    pub fn of<P, L>(device: &mut Device<L>, value: impl ValueOf<P>) -> Result<Self, Error>
    where
        P: SafetyFunctionParameter,
        L: Link<Protocol = CanOpen>,
    {
        let scale = P::read_scale(device)?;
        let raw = P::encode(value.into_value(), scale).map_err(named::<P>)?;
        P::check(&raw).map_err(named::<P>)?;
        let object = P::OBJECT;
        let mut bytes = [0u8; 4];
        let len = usize::from(object.bytes);
        let out = bytes.get_mut(..len).ok_or(Error::Value(
            ValueError::WrongLength {
                expected: 4,
                actual: len,
            }
            .named(P::NAME),
        ))?;
        raw.encode_le(out).map_err(named::<P>)?;
        let write =
            SdoWrite::from_le_bytes(object.index, object.subindex, out).ok_or(Error::Value(
                ValueError::WrongLength {
                    expected: 4,
                    actual: len,
                }
                .named(P::NAME),
            ))?;
        Ok(Self { write })
    }

    /// The object written.
    pub fn object(&self) -> (u16, u8) {
        (self.write.index, self.write.subindex)
    }

    /// The little-endian bytes written.
    pub fn data(&self) -> &[u8] {
        self.write.data()
    }
}

/// The signature of instance `function` of `signature` over the values `read` returns for each
/// signed object (`read(index, subindex, out)` fills `out`, the signed width, little-endian).
/// Pure: the writer reads the drive, a test can read a table.
pub fn function_signature<E>(
    signature: &FunctionSignature,
    function: u8,
    mut read: impl FnMut(u16, u8, &mut [u8]) -> Result<(), E>,
) -> Result<u16, E> {
    let mut digest = SIGNATURE_CRC.digest();
    let mut buf = [0u8; 4];
    // An absent object reads as zeros; the others as the drive (or the caller) gives them.
    let mut sign = |object: Option<(u16, u8)>, bytes: u8| -> Result<(), E> {
        let out = &mut buf[..usize::from(bytes.min(4))];
        out.fill(0);
        if let Some((index, subindex)) = object {
            read(index, subindex, out)?;
        }
        digest.update(out);
        Ok(())
    };
    for signed in signature.signed {
        match *signed {
            Signed::Each {
                index,
                first,
                last,
                bytes,
            } => {
                for subindex in first..=last {
                    sign(Some((index, subindex)), bytes)?;
                }
            }
            Signed::OfFunction { index, bytes } => sign(Some((index, function)), bytes)?,
            Signed::One {
                index,
                subindex,
                bytes,
            } => sign(Some((index, subindex)), bytes)?,
            Signed::Absent { bytes } => sign(None, bytes)?,
        }
    }
    Ok(digest.finalize())
}

/// Writes `values` to `node` over `bus`, then the recomputed signature of instance `function`
/// of `signature` (read back from the drive), and returns it.
///
/// Refused before any frame is sent: a `state` other than Pre-Operational
/// ([`SafetyWriteError::NotPreOperational`]), an instance the function does not have
/// ([`SafetyWriteError::NoSuchFunction`]) and a value the signature does not cover
/// ([`SafetyWriteError::NotSigned`]). A failed write or read stops the sequence with
/// [`SafetyWriteError::Bus`]; the signature is then not written, and the drive reports the
/// function's configuration invalid (6607h = 00h).
pub fn write_safety_function<B: SdoBus + ?Sized>(
    bus: &mut B,
    node: NodeId,
    state: NmtState,
    signature: &FunctionSignature,
    function: u8,
    values: &[SafetyValue],
) -> Result<u16, SafetyWriteError> {
    if state != NmtState::PreOperational {
        return Err(SafetyWriteError::NotPreOperational { state });
    }
    let stored_at = signature
        .stored_at(function)
        .ok_or(SafetyWriteError::NoSuchFunction {
            function: signature.name,
            instance: function,
        })?;
    if let Some(unsigned) = values
        .iter()
        .find(|v| !signature.covers(function, v.write.index, v.write.subindex))
    {
        return Err(SafetyWriteError::NotSigned {
            function: signature.name,
            index: unsigned.write.index,
            subindex: unsigned.write.subindex,
        });
    }
    let failed = |index, subindex| {
        move |cause| SafetyWriteError::Bus {
            index,
            subindex,
            cause,
        }
    };
    for value in values {
        let w = &value.write;
        bus.download(node, w.index, w.subindex, w.data())
            .map_err(failed(w.index, w.subindex))?;
    }
    let crc = function_signature(signature, function, |index, subindex, out| {
        let mut read = [0u8; 8];
        let len = bus
            .upload(node, index, subindex, &mut read)
            .map_err(failed(index, subindex))?;
        let take = len.min(out.len());
        out[..take].copy_from_slice(&read[..take]);
        Ok(())
    })?;
    bus.download(node, signature.index, stored_at, &crc.to_le_bytes())
        .map_err(failed(signature.index, stored_at))?;
    Ok(crc)
}
