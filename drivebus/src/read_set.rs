//! Batch reads: a tuple of parameter markers read in as few requests as the link allows.

use crate::device::{bus_error, named, raw_from, Device};
use crate::error::Error;
use crate::link::{Link, ReadRequest, MAX_VALUE_BYTES};
use crate::parameter::{Parameter, Readable};
use crate::{Protocol, VariantId};

/// A set of parameters that can be read together: tuples of up to twelve markers.
pub trait ReadSet<L: Link> {
    /// The engineering values, in the same order.
    type Values;
    /// Reads every member.
    fn read_from(self, device: &mut Device<L>) -> Result<Self::Values, Error>;
}

/// Where member `P` is read in `variant`: before the I/O of a batch read, blocking or async.
pub(crate) fn address_of<Pr: Protocol, P: Readable<Pr>>(
    variant: VariantId,
) -> Result<Pr::Address, Error> {
    P::read_address(variant).ok_or(Error::NotInVariant { parameter: P::NAME })
}

fn decode_member<L: Link, P: Readable<L::Protocol>>(
    device: &mut Device<L>,
    bytes: &[u8],
) -> Result<P::Value, Error> {
    let raw = raw_from::<P::Raw>(P::NAME, bytes)?;
    let scale = P::read_scale(device)?;
    P::decode(raw, scale).map_err(named::<P>)
}

/// Calls `$impl!` with every tuple a read set may be, up to twelve parameters: once for the
/// blocking [`ReadSet`], once for the async one.
macro_rules! for_each_tuple {
    ($impl:ident) => {
        $impl! {
            (A 0)
            (A 0, B 1)
            (A 0, B 1, C 2)
            (A 0, B 1, C 2, D 3)
            (A 0, B 1, C 2, D 3, E 4)
            (A 0, B 1, C 2, D 3, E 4, F 5)
            (A 0, B 1, C 2, D 3, E 4, F 5, G 6)
            (A 0, B 1, C 2, D 3, E 4, F 5, G 6, H 7)
            (A 0, B 1, C 2, D 3, E 4, F 5, G 6, H 7, I 8)
            (A 0, B 1, C 2, D 3, E 4, F 5, G 6, H 7, I 8, J 9)
            (A 0, B 1, C 2, D 3, E 4, F 5, G 6, H 7, I 8, J 9, K 10)
            (A 0, B 1, C 2, D 3, E 4, F 5, G 6, H 7, I 8, J 9, K 10, M 11)
        }
    };
}
#[cfg(feature = "async")]
pub(crate) use for_each_tuple;

macro_rules! read_set_for_tuples {
    ($( ($($p:ident $i:tt),+) )*) => {$(
        impl<L: Link, $($p: Readable<L::Protocol>),+> ReadSet<L> for ($($p,)+) {
            type Values = ($(<$p as Parameter>::Value,)+);

            fn read_from(self, device: &mut Device<L>) -> Result<Self::Values, Error> {
                let mut bufs = [[0u8; MAX_VALUE_BYTES]; [$($i),+].len()];
                let [$($p),+] = &mut bufs;
                let mut requests = [$(ReadRequest {
                    address: address_of::<L::Protocol, $p>(device.variant())?,
                    buf: &mut $p[..],
                    len: 0,
                }),+];
                device.link_mut().read_many(&mut requests).map_err(bus_error("read_many"))?;
                let lens = requests.map(|r| r.len);
                Ok(($(decode_member::<L, $p>(device, &bufs[$i][..lens[$i]])?,)+))
            }
        }
    )*};
}

#[allow(non_snake_case)]
mod tuples {
    use super::*;
    for_each_tuple!(read_set_for_tuples);
}
