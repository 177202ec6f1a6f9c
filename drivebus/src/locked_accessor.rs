//! [`LockedAccessor`]: a generated handle's view of a parameter that needs an unlock (a drive
//! with a `[lock]`): it reads; its `write` does not compile, because the parameter is written
//! through the guard an unlock returns, never through the handle.

use crate::device::Accessor;
use crate::error::Error;
use crate::link::Link;
use crate::parameter::{Readable, ValueOf, Writable};

/// The bound no parameter meets: a parameter that needs an unlock is written through the guard
/// `drive.unlock_<name>(..)` returns, never through the handle.
#[diagnostic::on_unimplemented(
    message = "`{Self}` is written only while the drive is unlocked",
    label = "needs an unlock",
    note = "unlock first (`let mut unlocked = drive.unlock_<name>(..)?;`) and write through the guard: `unlocked.<parameter>().write(..)`"
)]
pub trait WritableWithoutUnlock {}

/// A parameter that needs an unlock, seen from the handle: it can be read (awaited over an
/// async link); writing it does not compile (see [`WritableWithoutUnlock`]).
#[must_use = "an accessor does nothing until read"]
pub struct LockedAccessor<'d, L, P>(pub(crate) Accessor<'d, L, P>);

impl<'d, L, P> LockedAccessor<'d, L, P> {
    /// The read view of `accessor` (what a generated handle's accessor returns).
    pub fn new(accessor: Accessor<'d, L, P>) -> Self {
        Self(accessor)
    }
}

impl<L: Link, P: Readable<L::Protocol>> LockedAccessor<'_, L, P> {
    /// Reads the value in engineering units.
    #[inline]
    pub fn read(self) -> Result<P::Value, Error> {
        self.0.read()
    }

    /// Reads the raw value.
    #[inline]
    pub fn read_raw(self) -> Result<P::Raw, Error> {
        self.0.read_raw()
    }

    /// Does not compile: the parameter is written only while the drive is unlocked.
    pub fn write(self, value: impl ValueOf<P>) -> Result<(), Error>
    where
        P: WritableWithoutUnlock + Writable<L::Protocol>,
    {
        self.0.write(value)
    }

    /// Does not compile: the parameter is written only while the drive is unlocked.
    pub fn write_raw(self, raw: P::Raw) -> Result<(), Error>
    where
        P: WritableWithoutUnlock + Writable<L::Protocol>,
    {
        self.0.write_raw(raw)
    }
}
