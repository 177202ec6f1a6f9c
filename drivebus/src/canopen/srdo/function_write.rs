//! The safety-function write as a sans-I/O plan: which SDO write or read comes next, fed with
//! what each read returned, ending with the signature it wrote. The blocking
//! [`write_safety_function`](super::write_safety_function) and the async
//! [`write_safety_function_async`](super::write_safety_function_async) each only carry its steps
//! to the bus, so the sequence (refusals, values, read-back, signature) exists once.

use super::safety_function::{FunctionSignature, SafetyValue, SignedObjects};
use super::safety_write::SafetyWriteError;
use super::signature::SIGNATURE_CRC;
use crate::canopen::nmt::NmtState;
use crate::canopen::pdo::SdoWrite;
use crate::error::BusError;

/// The CRC the digest runs on, as a `static` so that the plan can hold its digest.
static CRC: crc::Crc<u16, crc::Table<16>> = SIGNATURE_CRC;

/// What the plan asks for next.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Step {
    /// Download this write (a value, then at last the signature).
    Write(SdoWrite),
    /// Upload `index`:`subindex` into [`FunctionWrite::buffer`].
    Read {
        /// Object index.
        index: u16,
        /// Sub-index.
        subindex: u8,
    },
    /// Done: the signature written.
    Done(u16),
}

/// The write of `values` and of the recomputed signature of one safety-function instance.
pub(super) struct FunctionWrite<'a> {
    values: core::slice::Iter<'a, SafetyValue>,
    signed: SignedObjects<'a>,
    digest: crc::Digest<'static, u16, crc::Table<16>>,
    /// The signed width of the read in flight; 0 while a write is.
    pending: u8,
    /// The object of the request in flight, for its error.
    asked: (u16, u8),
    /// Where a read's answer lands.
    buffer: [u8; 8],
    /// Where the signature goes: the function's signature object and the instance's sub-index.
    stored_at: (u16, u8),
    /// The signature, once every signed object was read; `Some` after it was written as well.
    signature: Option<u16>,
    written: bool,
}

impl<'a> FunctionWrite<'a> {
    /// The plan, or why it is refused before any frame is sent: a `state` other than
    /// Pre-Operational, an instance the function does not have, a value the signature of
    /// `function` does not cover.
    pub(super) fn new(
        state: NmtState,
        signature: &'a FunctionSignature,
        function: u8,
        values: &'a [SafetyValue],
    ) -> Result<Self, SafetyWriteError> {
        if state != NmtState::PreOperational {
            return Err(SafetyWriteError::NotPreOperational { state });
        }
        let stored_at = signature
            .stored_at(function)
            .ok_or(SafetyWriteError::NoSuchFunction {
                function: signature.name,
                instance: function,
            })?;
        if let Some(unsigned) = values.iter().find(|v| {
            let (index, subindex) = v.object();
            !signature.covers(function, index, subindex)
        }) {
            let (index, subindex) = unsigned.object();
            return Err(SafetyWriteError::NotSigned {
                function: signature.name,
                index,
                subindex,
            });
        }
        Ok(Self {
            values: values.iter(),
            signed: SignedObjects::new(signature, function),
            digest: CRC.digest(),
            pending: 0,
            asked: (0, 0),
            buffer: [0; 8],
            stored_at: (signature.index, stored_at),
            signature: None,
            written: false,
        })
    }

    /// The next step: the values' writes, the reads of what the signature covers (objects the
    /// table calls absent are signed as zeros without a read), the signature's write, done.
    pub(super) fn next_step(&mut self) -> Step {
        let step = self.step();
        self.asked = match step {
            Step::Write(w) => (w.index, w.subindex),
            Step::Read { index, subindex } => (index, subindex),
            Step::Done(_) => self.asked,
        };
        step
    }

    fn step(&mut self) -> Step {
        self.pending = 0;
        if let Some(value) = self.values.next() {
            return Step::Write(value.write());
        }
        let signature = match self.signature {
            Some(signature) => signature,
            None => match self.next_read() {
                Some(read) => return read,
                None => *self.signature.insert(self.digest.clone().finalize()),
            },
        };
        if self.written {
            return Step::Done(signature);
        }
        self.written = true;
        let (index, subindex) = self.stored_at;
        Step::Write(SdoWrite::u16(index, subindex, signature))
    }

    /// Where the upload of a [`Step::Read`] writes its answer.
    pub(super) fn buffer(&mut self) -> &mut [u8] {
        &mut self.buffer
    }

    /// The answer to the step just taken: a write's `Ok(_)`, a read's length in
    /// [`buffer`](Self::buffer) (its signed width enters the digest, a shorter answer padded
    /// with zeros), or the bus error that stops the sequence.
    pub(super) fn answered(
        &mut self,
        answer: Result<usize, BusError>,
    ) -> Result<(), SafetyWriteError> {
        let (index, subindex) = self.asked;
        let len = answer.map_err(|cause| SafetyWriteError::Bus {
            index,
            subindex,
            cause,
        })?;
        if self.pending > 0 {
            let buffer = self.buffer;
            self.sign(buffer.get(..len).unwrap_or(&buffer), self.pending);
        }
        Ok(())
    }

    /// The read of the next signed object that exists, signing absent ones on the way; `None`
    /// once every signed object is in the digest.
    fn next_read(&mut self) -> Option<Step> {
        while let Some(signed) = self.signed.next() {
            match signed.object {
                Some((index, subindex)) => {
                    self.pending = signed.bytes;
                    return Some(Step::Read { index, subindex });
                }
                None => self.sign(&[], signed.bytes),
            }
        }
        None
    }

    fn sign(&mut self, data: &[u8], bytes: u8) {
        let mut out = [0u8; 4];
        let out = &mut out[..usize::from(bytes.min(4))];
        let take = data.len().min(out.len());
        out[..take].copy_from_slice(&data[..take]);
        self.digest.update(out);
    }
}
