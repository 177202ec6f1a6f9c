//! [`Replay`]: how the async device runs the blocking code a generated crate writes once.
//!
//! A run-time scale (`runtime_scale`, generated) reads its inputs through a blocking
//! [`Device`]. The async device does not get a second, async copy of that code: it runs the
//! blocking code over a [`Replay`] link, which answers the reads it has answers for and notes the
//! first one it has none for. The async device then reads that address over its own link, adds
//! the answer and runs the code again, until it completes. A fixed scale reads nothing and runs
//! once; a run-time one runs once more per input (two at most in the descriptions so far).

use crate::device::Device;
use crate::error::{BusError, Error};
use crate::link::{Link, MAX_VALUE_BYTES};
use crate::Protocol;

/// Most distinct addresses one replayed computation reads.
const CAPACITY: usize = 8;

/// One read's outcome as the async link gave it: the bytes, or the bus error.
type Answer = Result<([u8; MAX_VALUE_BYTES], usize), BusError>;

/// A [`Link`] that answers from the reads made so far and notes the first one it cannot answer.
#[derive(Debug)]
pub(crate) struct Replay<P: Protocol> {
    answers: [Option<(P::Address, Answer)>; CAPACITY],
    missing: Option<P::Address>,
}

impl<P: Protocol> Replay<P> {
    fn new() -> Self {
        Self {
            answers: core::array::from_fn(|_| None),
            missing: None,
        }
    }

    /// Takes the address the last run needed and had no answer for.
    fn take_missing(&mut self) -> Option<P::Address> {
        self.missing.take()
    }

    /// Adds the async link's answer for `address`.
    fn answer(&mut self, address: P::Address, answer: Answer) {
        if let Some(free) = self.answers.iter_mut().find(|slot| slot.is_none()) {
            *free = Some((address, answer));
        }
    }
}

impl<P: Protocol> Link for Replay<P> {
    type Protocol = P;

    fn read(&mut self, address: &P::Address, out: &mut [u8]) -> Result<usize, BusError> {
        let known = self.answers.iter().flatten().find(|(a, _)| a == address);
        if let Some((_, answer)) = known {
            let (bytes, len) = answer.clone()?;
            let (from, to) = (bytes.get(..len), out.get_mut(..len));
            let (Some(from), Some(to)) = (from, to) else {
                return Err(BusError::Frame("value longer than its buffer"));
            };
            to.copy_from_slice(from);
            return Ok(len);
        }
        // With no room for the answer the run ends here, on this error.
        if self.answers.iter().any(Option::is_none) && self.missing.is_none() {
            self.missing = Some(*address);
        }
        Err(BusError::Unsupported(
            "more inputs than a replayed computation holds",
        ))
    }

    fn write(&mut self, _: &P::Address, _: &[u8]) -> Result<(), BusError> {
        Err(BusError::Unsupported(
            "a write inside a replayed computation",
        ))
    }

    fn wire_bytes(&self, _: &P::Address) -> usize {
        0
    }
}

/// Runs `compute` (blocking code over a [`Device`]) for an async device in `device`'s state,
/// reading what it reads with `read`, and returns its outcome.
pub(crate) async fn replayed<L, P: Protocol, T>(
    device: &mut Device<L>,
    compute: impl Fn(&mut Device<Replay<P>>) -> Result<T, Error>,
    mut read: impl AsyncFnMut(&mut L, P::Address, &mut [u8]) -> Result<usize, BusError>,
) -> Result<T, Error> {
    let mut replay = Device::new(Replay::<P>::new(), device.variant);
    replay.refusal = device.refusal;
    // The table is some 600 bytes: a handle given no values (most) copies none per read.
    if !device.given.is_empty() {
        replay.given = device.given;
    }
    loop {
        let outcome = compute(&mut replay);
        let Some(address) = replay.link.take_missing() else {
            return outcome;
        };
        let mut bytes = [0u8; MAX_VALUE_BYTES];
        let answer = read(&mut device.link, address, &mut bytes).await;
        replay.link.answer(address, answer.map(|len| (bytes, len)));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::canopen::{CanOpen, ObjectAddress};
    use crate::VariantId;
    use core::future::Future;
    use core::pin::pin;
    use core::task::{Context, Poll, Waker};

    fn ready<F: Future>(future: F) -> F::Output {
        let mut cx = Context::from_waker(Waker::noop());
        match pin!(future).poll(&mut cx) {
            Poll::Ready(value) => value,
            Poll::Pending => unreachable!("the test's reads are ready at once"),
        }
    }

    const A: ObjectAddress = ObjectAddress::new(0x2000, 1, 2);
    const B: ObjectAddress = ObjectAddress::new(0x2000, 2, 2);

    /// Reads A and B through a blocking device and adds their first bytes.
    fn sum(device: &mut Device<Replay<CanOpen>>) -> Result<u8, Error> {
        let mut buf = [0u8; 2];
        let bus = |cause| Error::Bus {
            parameter: "sum",
            cause,
        };
        device.link.read(&A, &mut buf).map_err(bus)?;
        let a = buf[0];
        device.link.read(&B, &mut buf).map_err(bus)?;
        Ok(a + buf[0])
    }

    #[test]
    fn each_input_is_read_once_and_the_computation_completes() {
        let mut device = Device::new(0u8, VariantId(0));
        let outcome = ready(replayed(
            &mut device,
            sum,
            async |reads: &mut u8, address, out| {
                *reads += 1;
                out[0] = if address == A { 3 } else { 4 };
                Ok(2)
            },
        ));
        assert_eq!(outcome, Ok(7));
        assert_eq!(device.link, 2);
    }

    #[test]
    fn the_computation_reads_the_values_the_handle_was_given() {
        let peak = crate::scale::Ratio::int(45);
        let given = |device: &mut Device<Replay<CanOpen>>| Ok(device.given().get("peak"));
        let mut device = Device::new((), VariantId(0));
        let none = async |_: &mut (), _, _: &mut [u8]| Err(BusError::Timeout);
        assert_eq!(ready(replayed(&mut device, given, none)), Ok(None));
        assert!(device.given_mut().set("peak", peak));
        assert_eq!(ready(replayed(&mut device, given, none)), Ok(Some(peak)));
    }

    #[test]
    fn a_failed_read_ends_the_computation_with_its_error() {
        let mut device = Device::new((), VariantId(0));
        let outcome = ready(replayed(
            &mut device,
            sum,
            async |_: &mut (), address, _: &mut [u8]| {
                if address == A {
                    Ok(2)
                } else {
                    Err(BusError::Timeout)
                }
            },
        ));
        assert_eq!(
            outcome,
            Err(Error::Bus {
                parameter: "sum",
                cause: BusError::Timeout
            })
        );
    }
}
