//! The bus trait RS-232 transports implement, and the [`Link`] generated drive handles use.

use super::data::{Answer, Object, Request};
use super::{ObjectAddress, Rs232, Rs232Error, StationId};
use crate::error::BusError;
use crate::link::Link;

/// A host able to exchange one request with one station at a time.
pub trait TelegramBus {
    /// Sends `request` to `station` and returns its answer: an upload's value or a download's
    /// confirmation. Every failure, an error answer included, is a [`BusError::Rs232Exchange`] naming the
    /// request's object, or an I/O error.
    fn exchange(&mut self, station: StationId, request: &Request) -> Result<Answer, BusError>;
}

impl<B: TelegramBus + ?Sized> TelegramBus for &mut B {
    fn exchange(&mut self, station: StationId, request: &Request) -> Result<Answer, BusError> {
        (**self).exchange(station, request)
    }
}

/// A host able to exchange one request with one station at a time, awaited: the async twin of
/// [`TelegramBus`], with the same contract. Dropping a future mid-exchange closes the exchange
/// (its stale bytes are drained before the next one).
#[cfg(feature = "async")]
#[allow(async_fn_in_trait)]
pub trait AsyncTelegramBus {
    /// Sends `request` to `station` and returns its answer, as [`TelegramBus::exchange`] does.
    async fn exchange(&mut self, station: StationId, request: &Request)
        -> Result<Answer, BusError>;
}

#[cfg(feature = "async")]
impl<B: AsyncTelegramBus + ?Sized> AsyncTelegramBus for &mut B {
    async fn exchange(
        &mut self,
        station: StationId,
        request: &Request,
    ) -> Result<Answer, BusError> {
        (**self).exchange(station, request).await
    }
}

impl Rs232Error {
    /// The bus error of this failure in an exchange about `object`.
    pub fn about(self, object: Object) -> BusError {
        BusError::Rs232Exchange {
            index: object.index,
            subindex: object.subindex,
            error: self,
        }
    }
}

/// A [`TelegramBus`] bound to one station: the [`Link`] generated drive handles use.
#[derive(Debug)]
pub struct Rs232Link<B> {
    bus: B,
    station: StationId,
}

// Unbounded: the same link serves a blocking and an async bus.
impl<B> Rs232Link<B> {
    /// Binds `bus` to `station`.
    pub fn new(bus: B, station: StationId) -> Self {
        Self { bus, station }
    }
    /// The station this link talks to.
    pub fn station(&self) -> StationId {
        self.station
    }
    /// The underlying bus.
    pub fn bus_mut(&mut self) -> &mut B {
        &mut self.bus
    }
    /// Gives the bus back.
    pub fn into_bus(self) -> B {
        self.bus
    }
}

/// The request that reads the value at `address`.
fn upload(address: &ObjectAddress) -> Request {
    Request::upload(address.index, address.subindex)
}

/// The request that writes `data` to `address`.
fn download(address: &ObjectAddress, data: &[u8]) -> Result<Request, BusError> {
    let object = Object {
        index: address.index,
        subindex: address.subindex,
    };
    Request::download(object.index, object.subindex, data).map_err(|error| error.about(object))
}

/// Copies an upload's value out of its answer into `out`; returns its length.
fn copy_value(answer: &Answer, out: &mut [u8]) -> Result<usize, BusError> {
    let value = answer.value().ok_or(BusError::Frame(
        "the bus answered an upload without a value",
    ))?;
    out.get_mut(..value.len())
        .ok_or(BusError::Frame("value buffer too small"))?
        .copy_from_slice(value);
    Ok(value.len())
}

impl<B: TelegramBus> Link for Rs232Link<B> {
    type Protocol = Rs232;

    fn read(&mut self, address: &ObjectAddress, out: &mut [u8]) -> Result<usize, BusError> {
        let answer = self.bus.exchange(self.station, &upload(address))?;
        copy_value(&answer, out)
    }

    fn write(&mut self, address: &ObjectAddress, data: &[u8]) -> Result<(), BusError> {
        let request = download(address, data)?;
        self.bus.exchange(self.station, &request).map(drop)
    }

    fn wire_bytes(&self, address: &ObjectAddress) -> usize {
        address.bytes as usize
    }
}

/// The async twin of the [`Link`] impl: the same requests and answers, awaited.
#[cfg(feature = "async")]
impl<B: AsyncTelegramBus> crate::asynch::AsyncLink for Rs232Link<B> {
    type Protocol = Rs232;

    async fn read(&mut self, address: &ObjectAddress, out: &mut [u8]) -> Result<usize, BusError> {
        let answer = self.bus.exchange(self.station, &upload(address)).await?;
        copy_value(&answer, out)
    }

    async fn write(&mut self, address: &ObjectAddress, data: &[u8]) -> Result<(), BusError> {
        let request = download(address, data)?;
        self.bus.exchange(self.station, &request).await.map(drop)
    }

    fn wire_bytes(&self, address: &ObjectAddress) -> usize {
        address.bytes as usize
    }
}
