//! The async device: [`Device<Async<L>>`](Device) reads and writes parameters over an
//! [`AsyncLink`], with the very checks of the blocking device.
//!
//! Every request first sends a lock command a dropped unlock guard owes ([`super::owed_lock`]).
//! Only the I/O is written here: what comes before it (the refusals, the range and the lock)
//! and after it (decoding, the lock's account) are the functions the blocking device calls too,
//! and run-time scales are the generated blocking code, replayed ([`super::replay`]).

use super::link::{Async, AsyncLink};
use super::read_set::AsyncReadSet;
use super::replay::{replayed, Replay};
use crate::device::{bus_error, integer_from, named, raw_from, within_bound, write_bytes, Device};
use crate::error::{BusError, Error};
use crate::link::MAX_VALUE_BYTES;
use crate::parameter::{RawInteger, Readable, Writable};
use crate::scale::Scale;
use crate::value::WireValue;

/// `self.settle().await?` (the lock a dropped guard owes, sent before the request), with the
/// common case, nothing owed, checked inline: no future is made or polled for it. A call per
/// check cost about 40 instructions, three per read (docs/benchmarks.md, issue 30).
macro_rules! settle {
    ($device:ident) => {
        if $device.owed_lock.is_some() {
            $device.settle().await?;
        }
    };
}

/// The address type of `L`'s protocol.
type AddressOf<L> = <<L as AsyncLink>::Protocol as crate::Protocol>::Address;

/// A scale function of a parameter, as the blocking code it is generated as.
type ScaleFn<L> = fn(&mut Device<Replay<<L as AsyncLink>::Protocol>>) -> Result<Scale, Error>;

impl<L: AsyncLink> Device<Async<L>> {
    /// Reads a parameter in engineering units.
    pub async fn read<P: Readable<L::Protocol>>(&mut self) -> Result<P::Value, Error> {
        settle!(self);
        let raw = self.read_raw::<P>().await?;
        let scale = self.scale(P::read_scale).await?;
        P::decode(raw, scale).map_err(named::<P>)
    }

    /// Reads a parameter's raw value, unscaled; refused as [`Device::read_raw`] refuses it.
    pub async fn read_raw<P: Readable<L::Protocol>>(&mut self) -> Result<P::Raw, Error> {
        self.read_raw_at::<P>(P::NAME, |address| address).await
    }

    /// [`Self::read_raw`] of `P` at the address `at` makes of `P`'s, errors naming `name`.
    pub(crate) async fn read_raw_at<P: Readable<L::Protocol>>(
        &mut self,
        name: &'static str,
        at: impl FnOnce(AddressOf<L>) -> AddressOf<L>,
    ) -> Result<P::Raw, Error> {
        settle!(self);
        let address = P::read_address(self.variant).map(at);
        let address = self.read_target(name, P::READ_AT.depends_on_variant(), address)?;
        let mut buf = [0u8; MAX_VALUE_BYTES];
        let len = self.link.0.read(&address, &mut buf).await;
        raw_from(name, &buf[..len.map_err(bus_error(name))?])
    }

    /// Another parameter's raw integer value (a bound before a write).
    pub(super) async fn read_integer(
        &mut self,
        parameter: &RawInteger<L::Protocol>,
    ) -> Result<i128, Error> {
        settle!(self);
        let address = parameter.read_at.get(self.variant);
        let address = self.read_target(
            parameter.name,
            parameter.read_at.depends_on_variant(),
            address,
        )?;
        let mut buf = [0u8; MAX_VALUE_BYTES];
        let len = self.link.0.read(&address, &mut buf).await;
        integer_from(parameter, &buf[..len.map_err(bus_error(parameter.name))?])
    }

    /// Writes a parameter in engineering units; checked as [`Device::write`] checks it.
    pub async fn write<P: Writable<L::Protocol>>(&mut self, value: P::Value) -> Result<(), Error> {
        settle!(self);
        let scale = self.scale(P::write_scale).await?;
        let raw = P::encode(value, scale).map_err(named::<P>)?;
        self.write_raw::<P>(raw).await
    }

    /// Writes a raw value; checked, refused, bounded and followed by the write lock as
    /// [`Device::write_raw`] does. A stop is neither refused nor bounded.
    pub async fn write_raw<P: Writable<L::Protocol>>(&mut self, raw: P::Raw) -> Result<(), Error> {
        self.write_raw_at::<P>(P::NAME, raw, |address| address)
            .await
    }

    /// [`Self::write_raw`] of `P` at the address `at` makes of `P`'s, errors naming `name`.
    pub(crate) async fn write_raw_at<P: Writable<L::Protocol>>(
        &mut self,
        name: &'static str,
        raw: P::Raw,
        at: impl FnOnce(AddressOf<L>) -> AddressOf<L>,
    ) -> Result<(), Error> {
        settle!(self);
        if self.write_checks::<P>(name, &raw)? {
            self.check_bounds::<P>(&raw).await?;
        }
        let address = P::write_address(self.variant)
            .map(at)
            .ok_or(Error::NotInVariant { parameter: name })?;
        let mut buf = [0u8; MAX_VALUE_BYTES];
        let bytes = write_bytes(name, &raw, self.link.0.wire_bytes(&address), &mut buf)?;
        let outcome = self.link.0.write(&address, bytes).await;
        self.written(name, bytes, outcome)
    }

    /// Reads the parameters that bound `P` and refuses `raw` beyond one's current value.
    async fn check_bounds<P: Writable<L::Protocol>>(&mut self, raw: &P::Raw) -> Result<(), Error> {
        let Some(raw) = raw.to_int() else {
            return Ok(());
        };
        for bound in P::BOUNDS {
            let limit = self.read_integer(&bound.by).await?;
            within_bound::<P, _>(bound, raw, limit)?;
        }
        Ok(())
    }

    /// Reads several parameters at once, in as few requests as the link can manage.
    pub async fn read_many<S: AsyncReadSet<L>>(&mut self, set: S) -> Result<S::Values, Error> {
        settle!(self);
        set.read_from(self).await
    }

    /// The scale `compute` (a parameter's `read_scale` or `write_scale`) gives, its inputs read
    /// over this device's link.
    pub(crate) async fn scale(&mut self, compute: ScaleFn<L>) -> Result<Scale, Error> {
        settle!(self);
        replayed(self, compute, read_over::<L>).await
    }
}

/// One read of a replayed computation, over the async link.
async fn read_over<L: AsyncLink>(
    link: &mut Async<L>,
    address: AddressOf<L>,
    out: &mut [u8],
) -> Result<usize, BusError> {
    link.0.read(&address, out).await
}
