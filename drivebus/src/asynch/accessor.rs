//! The accessors of an async handle: [`Accessor`], [`Indexed`] and [`LockedAccessor`] over
//! [`Async<L>`], with the methods of their blocking twins, awaited.

use super::link::{Async, AsyncLink};
use crate::device::{named, Accessor};
use crate::error::Error;
use crate::indexed::{at, member_of, Indexed, Run, SubIndexed};
use crate::locked_accessor::{LockedAccessor, WritableWithoutUnlock};
use crate::parameter::{Parameter, Readable, ValueOf, Writable};
use crate::Protocol;

impl<L: AsyncLink, P: Parameter> Accessor<'_, Async<L>, P> {
    /// Reads the value in engineering units.
    pub async fn read(self) -> Result<P::Value, Error>
    where
        P: Readable<L::Protocol>,
    {
        self.device.read::<P>().await
    }

    /// Reads the raw value.
    pub async fn read_raw(self) -> Result<P::Raw, Error>
    where
        P: Readable<L::Protocol>,
    {
        self.device.read_raw::<P>().await
    }

    /// Writes a value in engineering units: range-checked, and checked against the current
    /// values of the parameters that bound it (read first), before anything is sent.
    pub async fn write(self, value: impl ValueOf<P>) -> Result<(), Error>
    where
        P: Writable<L::Protocol>,
    {
        self.device.write::<P>(value.into_value()).await
    }

    /// Writes a raw value, checked as [`Self::write`] checks it.
    pub async fn write_raw(self, raw: P::Raw) -> Result<(), Error>
    where
        P: Writable<L::Protocol>,
    {
        self.device.write_raw::<P>(raw).await
    }

    /// Reads, changes and writes back the value.
    pub async fn modify(self, change: impl FnOnce(P::Value) -> P::Value) -> Result<(), Error>
    where
        P: Readable<L::Protocol> + Writable<L::Protocol>,
    {
        let value = self.device.read::<P>().await?;
        self.device.write::<P>(change(value)).await
    }
}

impl<L: AsyncLink, R: Run> Indexed<'_, Async<L>, R>
where
    <L::Protocol as Protocol>::Address: SubIndexed,
{
    /// Reads the value in engineering units.
    pub async fn read(self) -> Result<R::Value, Error>
    where
        R: Readable<L::Protocol>,
    {
        let sub = member_of::<R>(self.subindex)?;
        let raw = self.device.read_raw_at::<R>(R::NAME, at(sub)).await?;
        let scale = self.device.scale(R::read_scale).await?;
        R::decode(raw, scale).map_err(named::<R>)
    }

    /// Reads the raw value.
    pub async fn read_raw(self) -> Result<R::Raw, Error>
    where
        R: Readable<L::Protocol>,
    {
        let sub = member_of::<R>(self.subindex)?;
        self.device.read_raw_at::<R>(R::NAME, at(sub)).await
    }

    /// Writes a value in engineering units; range-checked before anything is sent.
    pub async fn write(self, value: impl ValueOf<R>) -> Result<(), Error>
    where
        R: Writable<L::Protocol>,
    {
        let sub = member_of::<R>(self.subindex)?;
        let scale = self.device.scale(R::write_scale).await?;
        let raw = R::encode(value.into_value(), scale).map_err(named::<R>)?;
        self.device.write_raw_at::<R>(R::NAME, raw, at(sub)).await
    }

    /// Writes a raw value; still checked against the description's range and allowed values.
    pub async fn write_raw(self, raw: R::Raw) -> Result<(), Error>
    where
        R: Writable<L::Protocol>,
    {
        let sub = member_of::<R>(self.subindex)?;
        self.device.write_raw_at::<R>(R::NAME, raw, at(sub)).await
    }
}

impl<L: AsyncLink, P: Readable<L::Protocol>> LockedAccessor<'_, Async<L>, P> {
    /// Reads the value in engineering units.
    pub async fn read(self) -> Result<P::Value, Error> {
        self.0.read().await
    }

    /// Reads the raw value.
    pub async fn read_raw(self) -> Result<P::Raw, Error> {
        self.0.read_raw().await
    }

    /// Does not compile: the parameter is written only while the drive is unlocked.
    pub async fn write(self, value: impl ValueOf<P>) -> Result<(), Error>
    where
        P: WritableWithoutUnlock + Writable<L::Protocol>,
    {
        self.0.write(value).await
    }

    /// Does not compile: the parameter is written only while the drive is unlocked.
    pub async fn write_raw(self, raw: P::Raw) -> Result<(), Error>
    where
        P: WritableWithoutUnlock + Writable<L::Protocol>,
    {
        self.0.write_raw(raw).await
    }
}
