//! Members described once over a run of sub-indices (`subindex = "1..=8"` in a description), as
//! device-driver's repeated registers: one marker type for the whole run, one accessor that takes
//! the sub-index and refuses one outside the run before anything is sent.
//!
//! The run's marker is an ordinary [`Parameter`] placed at the run's first sub-index; [`Run`]
//! adds the run's bounds. [`Indexed`] reaches sub-index `n` at run time (`drive.<name>(n)`), and
//! [`At<R, N>`] names one member as a type of its own where a type is needed
//! (`SafetyValue::of::<At<SlsVelocityLimitRun, 3>, _>`, `read_many`), named `<run>_<N>` as the
//! description's member is.

use core::marker::PhantomData;

use crate::canopen::ObjectAddress;
use crate::device::Device;
use crate::error::{Error, ValueError};
use crate::interpret::OutsideRange;
use crate::link::Link;
use crate::parameter::{Parameter, Readable, ValueOf, Writable};
use crate::scale::Scale;
use crate::{Protocol, VariantId};

/// A parameter described once over sub-indices [`Run::FIRST`]`..=`[`Run::LAST`] of one object;
/// its own placement is the first of them.
pub trait Run: Parameter {
    /// First sub-index of the run.
    const FIRST: u8;
    /// Last sub-index of the run (inclusive).
    const LAST: u8;
}

/// An address that names one sub-index of an object: the placement of a run's member.
pub trait SubIndexed: Copy {
    /// The same object at sub-index `subindex`.
    fn at_subindex(self, subindex: u8) -> Self;
}

impl SubIndexed for ObjectAddress {
    #[inline]
    fn at_subindex(self, subindex: u8) -> Self {
        Self { subindex, ..self }
    }
}

/// Sub-index `subindex` of run `R`, or the typed error for one outside it (nothing is sent).
pub(crate) fn member_of<R: Run>(subindex: u8) -> Result<u8, Error> {
    if (R::FIRST..=R::LAST).contains(&subindex) {
        return Ok(subindex);
    }
    Err(Error::Value(ValueError::OutOfRange {
        parameter: R::NAME,
        value: OutsideRange::Int {
            raw: subindex.into(),
            min: R::FIRST.into(),
            max: R::LAST.into(),
        },
    }))
}

/// A borrowed handle on sub-index `n` of run `R`: what `drive.<name>(n)` returns. Every
/// operation first checks `n` against the run ([`ValueError::OutOfRange`] naming the run, nothing
/// sent); errors after that name the run too.
#[must_use = "an accessor does nothing until read or written"]
pub struct Indexed<'d, L, R> {
    pub(crate) device: &'d mut Device<L>,
    pub(crate) subindex: u8,
    run: PhantomData<R>,
}

impl<'d, L, R> Indexed<'d, L, R> {
    /// Sub-index `subindex` of `R` on `device`; checked when read or written.
    pub fn new(device: &'d mut Device<L>, subindex: u8) -> Self {
        Self {
            device,
            subindex,
            run: PhantomData,
        }
    }

    /// The sub-index this accessor reaches.
    pub fn subindex(&self) -> u8 {
        self.subindex
    }
}

impl<L, R: Run> Indexed<'_, L, R> {
    /// First sub-index of the run.
    pub const FIRST: u8 = R::FIRST;
    /// Last sub-index of the run.
    pub const LAST: u8 = R::LAST;
}

impl<L: Link, R: Run> Indexed<'_, L, R>
where
    <L::Protocol as Protocol>::Address: SubIndexed,
{
    /// Reads the value in engineering units.
    pub fn read(self) -> Result<R::Value, Error>
    where
        R: Readable<L::Protocol>,
    {
        let raw = self
            .device
            .read_raw_at::<R>(R::NAME, at(member_of::<R>(self.subindex)?))?;
        let scale = R::read_scale(self.device)?;
        R::decode(raw, scale).map_err(|e| Error::Value(e.named(R::NAME)))
    }

    /// Reads the raw value.
    pub fn read_raw(self) -> Result<R::Raw, Error>
    where
        R: Readable<L::Protocol>,
    {
        let sub = member_of::<R>(self.subindex)?;
        self.device.read_raw_at::<R>(R::NAME, at(sub))
    }

    /// Writes a value in engineering units; range-checked before anything is sent.
    pub fn write(self, value: impl ValueOf<R>) -> Result<(), Error>
    where
        R: Writable<L::Protocol>,
    {
        let sub = member_of::<R>(self.subindex)?;
        let scale = R::write_scale(self.device)?;
        let raw =
            R::encode(value.into_value(), scale).map_err(|e| Error::Value(e.named(R::NAME)))?;
        self.device.write_raw_at::<R>(R::NAME, raw, at(sub))
    }

    /// Writes a raw value; still checked against the description's range and allowed values.
    pub fn write_raw(self, raw: R::Raw) -> Result<(), Error>
    where
        R: Writable<L::Protocol>,
    {
        let sub = member_of::<R>(self.subindex)?;
        self.device.write_raw_at::<R>(R::NAME, raw, at(sub))
    }
}

/// The placement of a member at `subindex`, from the run's.
pub(crate) fn at<A: SubIndexed>(subindex: u8) -> impl FnOnce(A) -> A {
    move |address| address.at_subindex(subindex)
}

/// Member `N` of run `R` as a marker type of its own, named `<run>_<N>`. A sub-index outside the
/// run does not compile.
pub struct At<R, const N: u8>(PhantomData<R>);

impl<R: Run, const N: u8> At<R, N> {
    /// `N`, checked against the run when the member is used.
    const SUBINDEX: u8 = {
        assert!(
            R::FIRST <= N && N <= R::LAST,
            "the sub-index is outside the run"
        );
        N
    };
}

impl<R: Run, const N: u8> Parameter for At<R, N> {
    const NAME: &'static str = MemberName::new(R::NAME, Self::SUBINDEX).as_str();
    const SCALE: Scale = R::SCALE;
    type Raw = R::Raw;
    type Value = R::Value;
    type Codec = R::Codec;

    #[inline]
    fn check(raw: &Self::Raw) -> Result<(), ValueError> {
        R::check(raw)
    }
    #[inline]
    fn stops(raw: &Self::Raw) -> bool {
        R::stops(raw)
    }
}

// A member is never what a missing capability should be fixed with (as `parameter!`'s impls).
#[diagnostic::do_not_recommend]
impl<P, R, const N: u8> Readable<P> for At<R, N>
where
    P: Protocol,
    P::Address: SubIndexed,
    R: Run + Readable<P>,
{
    const READ_AT: crate::Placement<P::Address> = R::READ_AT;
    #[inline]
    fn read_address(variant: VariantId) -> Option<P::Address> {
        R::read_address(variant).map(at(Self::SUBINDEX))
    }
    #[inline]
    fn read_scale<L: Link<Protocol = P>>(device: &mut Device<L>) -> Result<Scale, Error> {
        R::read_scale(device)
    }
}

#[diagnostic::do_not_recommend]
impl<P, R, const N: u8> Writable<P> for At<R, N>
where
    P: Protocol,
    P::Address: SubIndexed,
    R: Run + Writable<P>,
{
    const WRITE_AT: crate::Placement<P::Address> = R::WRITE_AT;
    #[inline]
    fn write_address(variant: VariantId) -> Option<P::Address> {
        R::write_address(variant).map(at(Self::SUBINDEX))
    }
    #[inline]
    fn write_scale<L: Link<Protocol = P>>(device: &mut Device<L>) -> Result<Scale, Error> {
        R::write_scale(device)
    }
}

// The value type of a member is its run's (a blanket impl: a member has no value type of its own
// for a wrong unit's error to name instead).
#[diagnostic::do_not_recommend]
impl<V: ValueOf<R>, R: Run, const N: u8> ValueOf<At<R, N>> for V {}

#[cfg(feature = "srdo")]
#[diagnostic::do_not_recommend]
impl<R, const N: u8> crate::canopen::srdo::SafetyFunctionParameter for At<R, N>
where
    R: Run + crate::canopen::srdo::SafetyFunctionParameter,
{
    const OBJECT: ObjectAddress =
        ObjectAddress::new(R::OBJECT.index, Self::SUBINDEX, R::OBJECT.bytes);
}

/// A member's name, `<run>_<sub-index>`, spelled at compile time.
struct MemberName {
    bytes: [u8; MemberName::CAPACITY],
    len: usize,
}

impl MemberName {
    /// Longest name spelled; a longer run name is cut (names are identifiers well below it).
    const CAPACITY: usize = 128;

    const fn new(run: &str, subindex: u8) -> Self {
        let mut bytes = [0u8; Self::CAPACITY];
        let run = run.as_bytes();
        let mut len = 0;
        // Room for `_` and three digits.
        while len < run.len() && len < Self::CAPACITY - 4 {
            bytes[len] = run[len];
            len += 1;
        }
        bytes[len] = b'_';
        len += 1;
        let digits = [subindex / 100, subindex / 10 % 10, subindex % 10];
        let skip = if subindex >= 100 {
            0
        } else if subindex >= 10 {
            1
        } else {
            2
        };
        let mut i = skip;
        while i < 3 {
            bytes[len] = b'0' + digits[i];
            len += 1;
            i += 1;
        }
        Self { bytes, len }
    }

    const fn as_str(&self) -> &str {
        let (name, _) = self.bytes.split_at(self.len);
        match core::str::from_utf8(name) {
            Ok(name) => name,
            // Only a run name cut inside a character is not UTF-8; names are identifiers.
            Err(_) => "",
        }
    }
}

#[cfg(all(test, feature = "std"))]
mod tests {
    use super::*;
    use crate::canopen::{CanOpenLink, NodeId};
    use crate::testing::MemoryBus;

    /// Sub-indices 2..=4 of 2000h, `u16`, read-write.
    struct Limit;
    crate::parameter!(Limit = "limit": u16 => u16, Plain, range(0, 1000);
        read canopen(0x2000 sub 2, 2 bytes); write canopen(0x2000 sub 2, 2 bytes));
    impl Run for Limit {
        const FIRST: u8 = 2;
        const LAST: u8 = 4;
    }

    fn device() -> Device<CanOpenLink<MemoryBus>> {
        let mut memory = MemoryBus::new();
        for sub in 2..=4u8 {
            memory.set_object(0x2000, sub, &u16::from(sub * 10).to_le_bytes());
        }
        Device::new(CanOpenLink::new(memory, NodeId(1)), VariantId(0))
    }

    #[test]
    fn a_member_is_reached_at_its_sub_index_and_named_after_it() {
        let mut device = device();
        assert_eq!(Indexed::<_, Limit>::new(&mut device, 3).read().unwrap(), 30);
        assert_eq!(device.read::<At<Limit, 4>>().unwrap(), 40);
        assert_eq!(<At<Limit, 4> as Parameter>::NAME, "limit_4");
        assert_eq!(
            <At<Limit, 2> as Readable<crate::canopen::CanOpen>>::read_address(VariantId(0)),
            Some(ObjectAddress::new(0x2000, 2, 2))
        );
        Indexed::<_, Limit>::new(&mut device, 4)
            .write(7u16)
            .unwrap();
        assert_eq!(device.read::<At<Limit, 4>>().unwrap(), 7);
    }

    #[test]
    fn a_sub_index_outside_the_run_is_refused_before_sending() {
        let mut device = device();
        for outside in [0, 1, 5, 255] {
            let err = Indexed::<_, Limit>::new(&mut device, outside)
                .read_raw()
                .unwrap_err();
            assert_eq!(
                err,
                Error::Value(ValueError::OutOfRange {
                    parameter: "limit",
                    value: OutsideRange::Int {
                        raw: outside.into(),
                        min: 2,
                        max: 4
                    },
                })
            );
            assert!(Indexed::<_, Limit>::new(&mut device, outside)
                .write_raw(1)
                .is_err());
        }
        assert!(device.link_mut().bus_mut().log().is_empty());
    }

    #[test]
    fn a_member_keeps_the_runs_range_check() {
        let mut device = device();
        assert!(Indexed::<_, Limit>::new(&mut device, 3)
            .write_raw(1001)
            .is_err());
        assert!(device.write_raw::<At<Limit, 3>>(1001).is_err());
    }

    #[test]
    fn member_names_spell_every_sub_index_width() {
        assert_eq!(MemberName::new("field", 1).as_str(), "field_1");
        assert_eq!(MemberName::new("field", 42).as_str(), "field_42");
        assert_eq!(MemberName::new("field", 254).as_str(), "field_254");
    }
}
