//! The lock an async unlock guard owes.
//!
//! A blocking unlock guard writes the drive's lock command when dropped. An async guard cannot:
//! `Drop` cannot await. Its `lock().await` writes the lock; a guard dropped without it (or
//! whose `lock()` was dropped before the drive answered) records on the device that the lock is
//! owed, and the device's next async request, whatever it is, first sends the lock command.
//! Until then the drive may still be unlocked; the handle's own account already counts it
//! locked, so no write to a locked parameter goes out in between.

use core::any::Any;

use super::link::{Async, AsyncLink};
use crate::device::{write_bytes, Device};
use crate::error::{Error, ValueError};
use crate::link::MAX_VALUE_BYTES;
use crate::parameter::Writable;
use crate::VariantId;

/// Most bytes an owed lock command occupies: a lock command is a short integer.
const MAX_LOCK_BYTES: usize = 16;

/// The address type of `L`'s protocol.
type AddressOf<L> = <<L as AsyncLink>::Protocol as crate::Protocol>::Address;

/// A lock command to send before the next request: its name, its bytes, and where it goes.
#[derive(Debug, Clone, Copy)]
pub struct OwedLock {
    name: &'static str,
    bytes: [u8; MAX_LOCK_BYTES],
    len: usize,
    /// Puts the command's address in the variant given into an `Option<address>`: the device's
    /// field cannot name its link's address type, so the address is handed over through `Any`.
    address: fn(VariantId, &mut dyn Any),
}

/// [`OwedLock::address`] of parameter `P` over `L`.
fn address_of<L: AsyncLink, P: Writable<L::Protocol>>(variant: VariantId, out: &mut dyn Any) {
    if let Some(slot) = out.downcast_mut::<Option<AddressOf<L>>>() {
        *slot = P::write_address(variant);
    }
}

impl<L: AsyncLink> Device<Async<L>> {
    /// Records that the write of `raw` to `P` (a lock command) is owed: the next async request
    /// through this device sends it first. The lock's account counts the drive locked from now
    /// on. This is what an async unlock guard dropped without `lock().await` does; an error
    /// means the command does not fit the record (longer than 16 bytes), and nothing is owed.
    pub fn owe_write<P: Writable<L::Protocol>>(&mut self, raw: P::Raw) -> Result<(), Error> {
        let address = P::write_address(self.variant);
        let wire_bytes = address.map_or(0, |a| self.link.0.wire_bytes(&a));
        let mut buf = [0u8; MAX_VALUE_BYTES];
        let bytes = write_bytes(P::NAME, &raw, wire_bytes, &mut buf)?;
        let mut owed = [0u8; MAX_LOCK_BYTES];
        owed.get_mut(..bytes.len())
            .ok_or(Error::Value(ValueError::WrongLength {
                expected: MAX_LOCK_BYTES,
                actual: bytes.len(),
            }))?
            .copy_from_slice(bytes);
        self.account_lock(P::NAME, bytes);
        self.owed_lock = Some(OwedLock {
            name: P::NAME,
            bytes: owed,
            len: bytes.len(),
            address: address_of::<L, P>,
        });
        Ok(())
    }

    /// Whether a lock command is owed (see [`Self::owe_write`]).
    pub fn lock_owed(&self) -> bool {
        self.owed_lock.is_some()
    }

    /// Sends the owed lock command, if any: before every async request. The record is cleared
    /// once the drive answered (a refusal as locked counts: the drive is locked), so a request
    /// dropped meanwhile leaves it owed. Any other failure is the request's error, and the lock
    /// stays owed.
    pub(crate) async fn settle(&mut self) -> Result<(), Error> {
        let Some(owed) = self.owed_lock else {
            return Ok(());
        };
        let mut address: Option<AddressOf<L>> = None;
        (owed.address)(self.variant, &mut address);
        let bytes = &owed.bytes[..owed.len];
        if let Some(address) = address {
            let outcome = self.link.0.write(&address, bytes).await;
            match self.written(owed.name, bytes, outcome) {
                Err(Error::Bus { cause, .. }) if !self.is_lock_refusal(&cause) => {
                    return Err(Error::Bus {
                        parameter: owed.name,
                        cause,
                    })
                }
                _ => {}
            }
        }
        self.owed_lock = None;
        Ok(())
    }
}
