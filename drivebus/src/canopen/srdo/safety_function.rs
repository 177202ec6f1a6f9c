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

use core::ops::RangeInclusive;

use super::function_write::{FunctionWrite, Step};
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
use crate::scale::Scale;
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
    /// The objects this entry signs in the signature of function `function`: the object's
    /// index (`None` for an absent one), the sub-indices in order, the width signed.
    fn run(&self, function: u8) -> (Option<u16>, RangeInclusive<u8>, u8) {
        match *self {
            Self::Each {
                index,
                first,
                last,
                bytes,
            } => (Some(index), first..=last, bytes),
            Self::OfFunction { index, bytes } => (Some(index), function..=function, bytes),
            Self::One {
                index,
                subindex,
                bytes,
            } => (Some(index), subindex..=subindex, bytes),
            Self::Absent { bytes } => (None, 0..=0, bytes),
        }
    }

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
    pub(super) fn stored_at(&self, function: u8) -> Option<u8> {
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

/// One object a signature signs, in table order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct SignedObject {
    /// Index and sub-index; `None` for an object the table says does not exist (zeros).
    pub(super) object: Option<(u16, u8)>,
    /// Bytes signed.
    pub(super) bytes: u8,
}

/// The objects the signature of one function instance signs, in order: each table entry
/// unrolled into its sub-indices.
#[derive(Debug, Clone)]
pub(super) struct SignedObjects<'a> {
    entries: core::slice::Iter<'a, Signed>,
    function: u8,
    run: Option<(Option<u16>, RangeInclusive<u8>, u8)>,
}

impl<'a> SignedObjects<'a> {
    /// The objects the signature of instance `function` of `signature` signs.
    pub(super) fn new(signature: &'a FunctionSignature, function: u8) -> Self {
        Self {
            entries: signature.signed.iter(),
            function,
            run: None,
        }
    }
}

impl Iterator for SignedObjects<'_> {
    type Item = SignedObject;

    fn next(&mut self) -> Option<SignedObject> {
        loop {
            if let Some((index, subindices, bytes)) = &mut self.run {
                if let Some(subindex) = subindices.next() {
                    return Some(SignedObject {
                        object: index.map(|index| (index, subindex)),
                        bytes: *bytes,
                    });
                }
            }
            self.run = Some(self.entries.next()?.run(self.function));
        }
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
        Self::scaled::<P>(value, scale)
    }

    /// [`SafetyValue::of`] on an async handle (feature `async`): the run-time factors are read
    /// over its async link. Nothing is written.
    #[cfg(feature = "async")]
    pub async fn of_async<P, L>(
        device: &mut Device<crate::asynch::Async<L>>,
        value: impl ValueOf<P>,
    ) -> Result<Self, Error>
    where
        P: SafetyFunctionParameter,
        L: crate::asynch::AsyncLink<Protocol = CanOpen>,
    {
        let scale = device.scale(P::read_scale).await?;
        Self::scaled::<P>(value, scale)
    }

    /// `value` of `P` at `scale`, range-checked and encoded for `P`'s object.
    fn scaled<P: SafetyFunctionParameter>(
        value: impl ValueOf<P>,
        scale: Scale,
    ) -> Result<Self, Error> {
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

    /// The SDO write of this value.
    pub(super) fn write(&self) -> SdoWrite {
        self.write
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
    for signed in SignedObjects::new(signature, function) {
        // An absent object reads as zeros; the others as the drive (or the caller) gives them.
        let out = &mut buf[..usize::from(signed.bytes.min(4))];
        out.fill(0);
        if let Some((index, subindex)) = signed.object {
            read(index, subindex, out)?;
        }
        digest.update(out);
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
    let mut plan = FunctionWrite::new(state, signature, function, values)?;
    loop {
        let answer = match plan.next_step() {
            Step::Write(w) => bus
                .download(node, w.index, w.subindex, w.data())
                .map(|()| 0),
            Step::Read { index, subindex } => bus.upload(node, index, subindex, plan.buffer()),
            Step::Done(signature) => return Ok(signature),
        };
        plan.answered(answer)?;
    }
}

/// [`write_safety_function`] over an async SDO client (feature `async`): the same refusals
/// before any frame and the same writes and reads in the same order, each awaited. A future
/// dropped mid-way stops the sequence as a failed write does: the signature is not written.
#[cfg(feature = "async")]
pub async fn write_safety_function_async<B: crate::canopen::link::AsyncSdoBus + ?Sized>(
    bus: &mut B,
    node: NodeId,
    state: NmtState,
    signature: &FunctionSignature,
    function: u8,
    values: &[SafetyValue],
) -> Result<u16, SafetyWriteError> {
    let mut plan = FunctionWrite::new(state, signature, function, values)?;
    loop {
        let answer = match plan.next_step() {
            Step::Write(w) => bus
                .download(node, w.index, w.subindex, w.data())
                .await
                .map(|()| 0),
            Step::Read { index, subindex } => {
                bus.upload(node, index, subindex, plan.buffer()).await
            }
            Step::Done(signature) => return Ok(signature),
        };
        plan.answered(answer)?;
    }
}
