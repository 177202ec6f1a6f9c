//! A drive handle's engine: reads and writes parameters over a [`Link`].

use core::marker::PhantomData;

use crate::bound::OutsideBound;
use crate::error::{BusError, Error, ValueError, WriteRefusal};
use crate::given::Given;
use crate::link::{Link, MAX_VALUE_BYTES};
use crate::parameter::{BoundBy, Parameter, RawInteger, Readable, ValueOf, Writable};
use crate::read_set::ReadSet;
use crate::value::WireValue;
use crate::write_lock::{LockAccount, WriteLock};
use crate::VariantId;

/// A link plus the device's selected variant; generated drive handles wrap one.
#[derive(Debug)]
pub struct Device<L> {
    pub(crate) link: L,
    pub(crate) variant: VariantId,
    /// Set while the drive is not one the description covers: every write fails before sending.
    pub(crate) refusal: Option<WriteRefusal>,
    /// The drive's write lock and the unlocks sent through this handle, if it has a lock: a
    /// write to a locked parameter fails before sending.
    lock: Option<LockAccount>,
    /// Values given when the handle was opened (model constants, unreadable scale inputs).
    pub(crate) given: Given,
    /// The lock command a dropped async unlock guard owes: sent before the next async request.
    #[cfg(feature = "async")]
    pub(crate) owed_lock: Option<crate::asynch::OwedLock>,
}

/// The address type of `L`'s protocol.
type ProtocolAddress<L> = <<L as Link>::Protocol as crate::Protocol>::Address;

pub(crate) fn bus_error(parameter: &'static str) -> impl Fn(BusError) -> Error {
    move |cause| Error::Bus { parameter, cause }
}

// What needs no I/O: one impl for the blocking and the async device.
impl<L> Device<L> {
    /// A device reached over `link`, in configuration `variant`.
    pub fn new(link: L, variant: VariantId) -> Self {
        Self {
            link,
            variant,
            refusal: None,
            lock: None,
            given: Given::default(),
            #[cfg(feature = "async")]
            owed_lock: None,
        }
    }

    /// The device behind a write lock (`[lock]` in its description, the generated
    /// `WRITE_LOCK`): it starts locked, as the drive powers up, and writes to a locked
    /// parameter are refused until a grant that opens it is written through this handle (see
    /// [`crate::write_lock`]).
    pub fn with_write_lock(mut self, lock: &'static WriteLock<'static>) -> Self {
        self.lock = Some(LockAccount::locked(lock));
        self
    }

    /// The values the handle was given when opened (model constants, unreadable scale inputs).
    pub fn given(&self) -> &Given {
        &self.given
    }

    /// The given values, to add to.
    pub fn given_mut(&mut self) -> &mut Given {
        &mut self.given
    }

    /// The selected variant.
    pub fn variant(&self) -> VariantId {
        self.variant
    }

    /// Selects another variant (after reading the drive's configuration, or as the user's
    /// explicit override); lifts a refusal of writes for an unknown variant.
    pub fn set_variant(&mut self, variant: VariantId) {
        self.variant = variant;
        if matches!(self.refusal, Some(WriteRefusal::UnknownVariant { .. })) {
            self.refusal = None;
        }
    }

    /// Refuses every write from now on, with `reason`, until it is lifted.
    pub fn refuse_writes(&mut self, reason: WriteRefusal) {
        self.refusal = Some(reason);
    }

    /// Lifts the refusal of every write: the caller's explicit decision to write to a drive its
    /// description was not verified against (the generated `trust_unverified`). A locked
    /// parameter stays refused until an unlock opens it.
    pub fn lift_write_refusal(&mut self) {
        self.refusal = None;
    }

    /// Why every write is refused, if it is.
    pub fn write_refusal(&self) -> Option<WriteRefusal> {
        self.refusal
    }

    /// Why a write to `P` would be refused before sending, if it would: the refusal of every
    /// write, else the write lock.
    pub fn write_refusal_of<P: Parameter>(&self) -> Option<WriteRefusal> {
        self.refusal
            .or_else(|| self.lock.as_ref()?.refusal(P::NAME))
    }

    /// The link, for protocol-specific operations.
    pub fn link_mut(&mut self) -> &mut L {
        &mut self.link
    }

    /// Gives the link back.
    pub fn into_link(self) -> L {
        self.link
    }

    /// A typed accessor for parameter `P`.
    pub fn parameter<P: Parameter>(&mut self) -> Accessor<'_, L, P> {
        Accessor {
            device: self,
            parameter: PhantomData,
        }
    }

    /// Where a read of parameter `name` goes: `address`, its address in the current variant
    /// (`by_variant`: whether that address depends on the variant), unless the parameter cannot
    /// be read now. Before the I/O of every read, blocking or async.
    pub(crate) fn read_target<A>(
        &self,
        name: &'static str,
        by_variant: bool,
        address: Option<A>,
    ) -> Result<A, Error> {
        if let Some(WriteRefusal::UnknownVariant { selector, value }) = self.refusal {
            if by_variant {
                return Err(Error::VariantUnknown {
                    parameter: name,
                    selector,
                    value,
                });
            }
        }
        address.ok_or(Error::NotInVariant { parameter: name })
    }

    /// The checks of a write of `raw` to `P` (errors naming `name`) that need no I/O: the range
    /// and allowed values, then the refusal of writes and the lock. Returns whether the write
    /// is bounded (its bounds are read next): a stop is neither refused nor bounded.
    pub(crate) fn write_checks<P: Parameter>(
        &self,
        name: &'static str,
        raw: &P::Raw,
    ) -> Result<bool, Error> {
        P::check(raw).map_err(|e| Error::Value(e.named(name)))?;
        let stops = P::stops(raw);
        let refusal = self.refusal.or_else(|| self.lock.as_ref()?.refusal(name));
        if let Some(reason) = refusal.filter(|_| !stops) {
            return Err(Error::WritesRefused {
                parameter: name,
                reason,
            });
        }
        Ok(!stops)
    }

    /// The lock's account follows a write of `bytes` to `name` that is as good as sent (an
    /// owed lock command).
    #[cfg(feature = "async")]
    pub(crate) fn account_lock(&mut self, name: &'static str, bytes: &[u8]) {
        if let Some(lock) = &mut self.lock {
            lock.follow(name, bytes, &Ok(()));
        }
    }

    /// Whether `cause` is the drive refusing a write as locked.
    #[cfg(feature = "async")]
    pub(crate) fn is_lock_refusal(&self, cause: &BusError) -> bool {
        self.lock
            .as_ref()
            .is_some_and(|lock| lock.is_refusal(cause))
    }

    /// After a write's I/O: the lock's account follows what was sent and how it ended.
    pub(crate) fn written(
        &mut self,
        name: &'static str,
        bytes: &[u8],
        outcome: Result<(), BusError>,
    ) -> Result<(), Error> {
        if let Some(lock) = &mut self.lock {
            lock.follow(name, bytes, &outcome);
        }
        outcome.map_err(bus_error(name))
    }
}

/// The raw value of parameter `name` from the bytes read: after the I/O of every read.
pub(crate) fn raw_from<R: WireValue>(name: &'static str, bytes: &[u8]) -> Result<R, Error> {
    R::decode_le(bytes).map_err(|e| Error::Value(e.named(name)))
}

/// The integer value of `parameter` from the bytes read (a bound, an identity parameter).
pub(crate) fn integer_from<Pr: crate::Protocol>(
    parameter: &RawInteger<Pr>,
    bytes: &[u8],
) -> Result<i128, Error> {
    (parameter.decode)(bytes).map_err(|e| Error::Value(e.named(parameter.name)))
}

/// Refuses a write of `raw` to `P` that lies beyond `limit`, the current value of `bound`'s
/// parameter.
pub(crate) fn within_bound<P: Parameter, Pr: crate::Protocol>(
    bound: &BoundBy<Pr>,
    raw: i128,
    limit: i128,
) -> Result<(), Error> {
    if bound.bound.breached(raw, limit) {
        return Err(Error::OutsideBound(OutsideBound {
            parameter: P::NAME,
            bound: bound.by.name,
            raw,
            limit,
        }));
    }
    Ok(())
}

/// The little-endian bytes of a write of `raw` (errors naming `name`), `wire_bytes` long (0:
/// the raw type's own length), in `buf`: before the I/O of every write.
pub(crate) fn write_bytes<'b, R: WireValue>(
    name: &'static str,
    raw: &R,
    wire_bytes: usize,
    buf: &'b mut [u8; MAX_VALUE_BYTES],
) -> Result<&'b [u8], Error> {
    let len = match wire_bytes {
        0 => R::WIRE_BYTES,
        n => n,
    };
    let bytes = buf
        .get_mut(..len)
        .ok_or(Error::Value(ValueError::WrongLength {
            expected: MAX_VALUE_BYTES,
            actual: len,
        }))?;
    raw.encode_le(bytes)
        .map_err(|e| Error::Value(e.named(name)))?;
    Ok(bytes)
}

impl<L: Link> Device<L> {
    /// Reads a parameter in engineering units.
    pub fn read<P: Readable<L::Protocol>>(&mut self) -> Result<P::Value, Error> {
        let raw = self.read_raw::<P>()?;
        let scale = P::read_scale(self)?;
        P::decode(raw, scale).map_err(|e| named::<P>(e))
    }

    /// Reads a parameter's raw value, unscaled.
    /// While the drive reported a variant the description does not cover, a parameter whose
    /// address depends on the variant is not read ([`Error::VariantUnknown`]): nothing is guessed.
    pub fn read_raw<P: Readable<L::Protocol>>(&mut self) -> Result<P::Raw, Error> {
        self.read_raw_at::<P>(P::NAME, |address| address)
    }

    /// [`Self::read_raw`] of `P` at the address `at` makes of `P`'s, errors naming `name`: one
    /// member of a sub-index run ([`crate::indexed`]).
    pub(crate) fn read_raw_at<P: Readable<L::Protocol>>(
        &mut self,
        name: &'static str,
        at: impl FnOnce(ProtocolAddress<L>) -> ProtocolAddress<L>,
    ) -> Result<P::Raw, Error> {
        let mut buf = [0u8; MAX_VALUE_BYTES];
        // `read_address`, not `READ_AT`: a run's member moves its run's placement.
        let address = self.read_target(
            name,
            P::READ_AT.depends_on_variant(),
            P::read_address(self.variant).map(at),
        )?;
        let len = self
            .link
            .read(&address, &mut buf)
            .map_err(bus_error(name))?;
        raw_from(name, &buf[..len])
    }

    /// Reads another parameter's raw integer value: a bound before a write, an identity
    /// parameter on connect. The same request, and the same refusals, as [`Self::read_raw`].
    pub(crate) fn read_integer(
        &mut self,
        parameter: &RawInteger<L::Protocol>,
    ) -> Result<i128, Error> {
        let mut buf = [0u8; MAX_VALUE_BYTES];
        let address = parameter.read_at.get(self.variant);
        let address = self.read_target(
            parameter.name,
            parameter.read_at.depends_on_variant(),
            address,
        )?;
        let len = (self.link.read(&address, &mut buf)).map_err(bus_error(parameter.name))?;
        integer_from(parameter, &buf[..len])
    }

    /// Writes a parameter in engineering units; range-checked before anything is sent.
    pub fn write<P: Writable<L::Protocol>>(&mut self, value: P::Value) -> Result<(), Error> {
        let scale = P::write_scale(self)?;
        let raw = P::encode(value, scale).map_err(named::<P>)?;
        self.write_raw::<P>(raw)
    }

    /// Writes a raw value; still checked against the description's range and allowed values,
    /// and against the current values of the parameters that bound it ([`Writable::BOUNDS`],
    /// read first). Refused before sending while writes are refused
    /// ([`Self::write_refusal_of`]). A write that stops the drive ([`crate::stop`]) is neither
    /// refused nor bounded: a stop is always sent and the drive's answer returned.
    pub fn write_raw<P: Writable<L::Protocol>>(&mut self, raw: P::Raw) -> Result<(), Error> {
        self.write_raw_at::<P>(P::NAME, raw, |address| address)
    }

    /// [`Self::write_raw`] of `P` at the address `at` makes of `P`'s, errors and the write lock
    /// naming `name`: one member of a sub-index run ([`crate::indexed`]).
    pub(crate) fn write_raw_at<P: Writable<L::Protocol>>(
        &mut self,
        name: &'static str,
        raw: P::Raw,
        at: impl FnOnce(ProtocolAddress<L>) -> ProtocolAddress<L>,
    ) -> Result<(), Error> {
        if self.write_checks::<P>(name, &raw)? {
            self.check_bounds::<P>(&raw)?;
        }
        let address = P::write_address(self.variant)
            .map(at)
            .ok_or(Error::NotInVariant { parameter: name })?;
        let mut buf = [0u8; MAX_VALUE_BYTES];
        let bytes = write_bytes(name, &raw, self.link.wire_bytes(&address), &mut buf)?;
        let outcome = self.link.write(&address, bytes);
        self.written(name, bytes, outcome)
    }

    /// Reads the parameters that bound `P` and refuses `raw` if it lies beyond one's current
    /// value. Bounds compare integers; the description's validation keeps them to integer
    /// parameters, so a raw value without an integer (a float) has none.
    fn check_bounds<P: Writable<L::Protocol>>(&mut self, raw: &P::Raw) -> Result<(), Error> {
        let Some(raw) = raw.to_int() else {
            return Ok(());
        };
        for bound in P::BOUNDS {
            let limit = self.read_integer(&bound.by)?;
            within_bound::<P, _>(bound, raw, limit)?;
        }
        Ok(())
    }

    /// Reads several parameters at once, in as few requests as the link can manage.
    pub fn read_many<S: ReadSet<L>>(&mut self, set: S) -> Result<S::Values, Error> {
        set.read_from(self)
    }
}

/// Fills in the parameter name of a value error raised below the parameter layer.
pub(crate) fn named<P: Parameter>(error: ValueError) -> Error {
    Error::Value(error.named(P::NAME))
}

/// A borrowed handle on one parameter of a device: `drive.bus_dc_link().read()`.
#[must_use = "an accessor does nothing until read or written"]
pub struct Accessor<'d, L, P> {
    pub(crate) device: &'d mut Device<L>,
    parameter: PhantomData<P>,
}

impl<L: Link, P: Parameter> Accessor<'_, L, P> {
    /// Reads the value in engineering units.
    #[inline]
    pub fn read(self) -> Result<P::Value, Error>
    where
        P: Readable<L::Protocol>,
    {
        self.device.read::<P>()
    }

    /// Reads the raw value.
    #[inline]
    pub fn read_raw(self) -> Result<P::Raw, Error>
    where
        P: Readable<L::Protocol>,
    {
        self.device.read_raw::<P>()
    }

    /// Writes a value in engineering units: range-checked, and checked against the current
    /// values of the parameters that bound it (read first), before anything is sent.
    #[inline]
    pub fn write(self, value: impl ValueOf<P>) -> Result<(), Error>
    where
        P: Writable<L::Protocol>,
    {
        self.device.write::<P>(value.into_value())
    }

    /// Writes a raw value, checked as [`Self::write`] checks it.
    #[inline]
    pub fn write_raw(self, raw: P::Raw) -> Result<(), Error>
    where
        P: Writable<L::Protocol>,
    {
        self.device.write_raw::<P>(raw)
    }

    /// Reads, changes and writes back the value.
    pub fn modify(self, change: impl FnOnce(P::Value) -> P::Value) -> Result<(), Error>
    where
        P: Readable<L::Protocol> + Writable<L::Protocol>,
    {
        let value = self.device.read::<P>()?;
        self.device.write::<P>(change(value))
    }
}
