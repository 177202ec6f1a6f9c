//! [`AsyncReadSet`]: the async twin of [`ReadSet`](crate::read_set::ReadSet), a tuple of
//! parameter markers read in as few requests as the link allows.

use super::link::{Async, AsyncLink};
use crate::device::{bus_error, named, raw_from, Device};
use crate::error::Error;
use crate::link::{ReadRequest, MAX_VALUE_BYTES};
use crate::parameter::{Parameter, Readable};
use crate::read_set::address_of;

/// A set of parameters that can be read together over an async link: tuples of up to twelve
/// markers.
#[allow(async_fn_in_trait)] // as `AsyncLink`: no `Send` bound that single-threaded executors lack
pub trait AsyncReadSet<L: AsyncLink> {
    /// The engineering values, in the same order.
    type Values;
    /// Reads every member.
    async fn read_from(self, device: &mut Device<Async<L>>) -> Result<Self::Values, Error>;
}

/// Member `P`'s value from the bytes read for it; its scale's inputs are read after the batch.
async fn member<L: AsyncLink, P: Readable<L::Protocol>>(
    device: &mut Device<Async<L>>,
    bytes: &[u8],
) -> Result<P::Value, Error> {
    let raw = raw_from::<P::Raw>(P::NAME, bytes)?;
    let scale = device.scale(P::read_scale).await?;
    P::decode(raw, scale).map_err(named::<P>)
}

macro_rules! async_read_set_for_tuples {
    ($( ($($p:ident $i:tt),+) )*) => {$(
        impl<L: AsyncLink, $($p: Readable<L::Protocol>),+> AsyncReadSet<L> for ($($p,)+) {
            type Values = ($(<$p as Parameter>::Value,)+);

            async fn read_from(self, device: &mut Device<Async<L>>) -> Result<Self::Values, Error> {
                let mut bufs = [[0u8; MAX_VALUE_BYTES]; [$($i),+].len()];
                let [$($p),+] = &mut bufs;
                let mut requests = [$(ReadRequest {
                    address: address_of::<L::Protocol, $p>(device.variant())?,
                    buf: &mut $p[..],
                    len: 0,
                }),+];
                let outcome = device.link.0.read_many(&mut requests).await;
                outcome.map_err(bus_error("read_many"))?;
                let lens = requests.map(|r| r.len);
                Ok(($(member::<L, $p>(device, &bufs[$i][..lens[$i]]).await?,)+))
            }
        }
    )*};
}

#[allow(non_snake_case)]
mod tuples {
    use super::*;
    crate::read_set::for_each_tuple!(async_read_set_for_tuples);
}
