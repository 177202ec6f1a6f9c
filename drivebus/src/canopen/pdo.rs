//! PDOs: the configuration sequence as a plan of SDO writes, and bit-packed payload codecs.
//!
//! A mapping is checked at compile time when built as a constant:
//!
//! ```
//! use drivebus::canopen::pdo::{MappedObject, PdoLayout};
//! const STATUS: PdoLayout<2> = PdoLayout::new([
//!     MappedObject::new(0x6041, 0, 16), // statusword
//!     MappedObject::new(0x6064, 0, 32), // position actual value
//! ]);
//! let payload = [0x37, 0x02, 0x10, 0x27, 0x00, 0x00];
//! assert_eq!(STATUS.get::<u16>(&payload, 0), Ok(0x0237));
//! assert_eq!(STATUS.get::<i32>(&payload, 1), Ok(10_000));
//! ```
//!
//! ```compile_fail
//! use drivebus::canopen::pdo::{MappedObject, PdoLayout};
//! // 3 × 32 bits do not fit 8 bytes: the constant fails to evaluate.
//! const TOO_BIG: PdoLayout<3> = PdoLayout::new([MappedObject::new(0x6064, 0, 32); 3]);
//! let _ = TOO_BIG;
//! ```

use super::address::NodeId;
use super::link::SdoBus;
use crate::error::{BusError, ValueError};
use crate::parameter::Parameter;

#[cfg(feature = "std")]
pub use drivebus_model::canopen::PdoSetup;
pub use drivebus_model::canopen::{mapping_bits, mapping_fits, MappedObject, PdoKind};

/// A value that can be carried in a PDO entry.
pub trait PdoValue: Sized {
    /// Widest entry the type can hold.
    const BITS: u8;
    /// The value of the low `bits` bits of `raw` (sign-extended for signed types).
    fn from_raw(raw: u64, bits: u8) -> Self;
    /// The value's bits (the codec keeps the entry's low bits).
    fn to_raw(self) -> u64;
}

macro_rules! unsigned_values {
    ($($t:ty),*) => {$(
        impl PdoValue for $t {
            const BITS: u8 = <$t>::BITS as u8;
            fn from_raw(raw: u64, _bits: u8) -> Self {
                raw as $t
            }
            fn to_raw(self) -> u64 {
                self as u64
            }
        }
    )*};
}
macro_rules! signed_values {
    ($($t:ty),*) => {$(
        impl PdoValue for $t {
            const BITS: u8 = <$t>::BITS as u8;
            fn from_raw(raw: u64, bits: u8) -> Self {
                // Sign-extend from the entry's width (INTEGER24 and friends).
                let shift = 64 - u32::from(bits);
                (((raw << shift) as i64) >> shift) as $t
            }
            fn to_raw(self) -> u64 {
                self as i64 as u64
            }
        }
    )*};
}
unsigned_values!(u8, u16, u32, u64);
signed_values!(i8, i16, i32, i64);

impl PdoValue for bool {
    const BITS: u8 = 1;
    fn from_raw(raw: u64, _bits: u8) -> Self {
        raw & 1 != 0
    }
    fn to_raw(self) -> u64 {
        u64::from(self)
    }
}

impl PdoValue for f32 {
    const BITS: u8 = 32;
    fn from_raw(raw: u64, _bits: u8) -> Self {
        f32::from_bits(raw as u32)
    }
    fn to_raw(self) -> u64 {
        u64::from(self.to_bits())
    }
}

impl PdoValue for f64 {
    const BITS: u8 = 64;
    fn from_raw(raw: u64, _bits: u8) -> Self {
        f64::from_bits(raw)
    }
    fn to_raw(self) -> u64 {
        self.to_bits()
    }
}

/// A checked PDO mapping with precomputed bit offsets.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PdoLayout<const N: usize> {
    entries: [MappedObject; N],
    offsets: [u8; N],
    bytes: u8,
}

impl<const N: usize> PdoLayout<N> {
    /// The layout of `entries`, packed from bit 0 in order. Panics (a compile error in a
    /// constant) if the mapping does not fit 8 bytes.
    pub const fn new(entries: [MappedObject; N]) -> Self {
        assert!(mapping_fits(&entries), "PDO mapping does not fit 8 bytes");
        let mut offsets = [0u8; N];
        let mut offset = 0u32;
        let mut i = 0;
        while i < N {
            offsets[i] = offset as u8;
            offset += entries[i].bits as u32;
            i += 1;
        }
        Self {
            entries,
            offsets,
            bytes: offset.div_ceil(8) as u8,
        }
    }

    /// The mapped entries.
    pub const fn entries(&self) -> &[MappedObject; N] {
        &self.entries
    }

    /// Payload length in bytes.
    pub const fn len(&self) -> usize {
        self.bytes as usize
    }

    /// Whether nothing is mapped.
    pub const fn is_empty(&self) -> bool {
        N == 0
    }

    fn slot(&self, i: usize) -> Result<(u32, u8), ValueError> {
        let entry = self.entries.get(i).ok_or(ValueError::Overflow {
            parameter: "PDO entry index",
        })?;
        Ok((u32::from(self.offsets[i]), entry.bits))
    }

    fn check_len(&self, payload: &[u8]) -> Result<u64, ValueError> {
        if payload.len() < self.len() {
            return Err(ValueError::WrongLength {
                expected: self.len(),
                actual: payload.len(),
            });
        }
        let mut word = [0u8; 8];
        word[..self.len()].copy_from_slice(&payload[..self.len()]);
        Ok(u64::from_le_bytes(word))
    }

    /// The raw bits of entry `i`.
    pub fn get_raw(&self, payload: &[u8], i: usize) -> Result<u64, ValueError> {
        let (offset, bits) = self.slot(i)?;
        let word = self.check_len(payload)?;
        Ok((word >> offset) & mask(bits))
    }

    /// Entry `i` as a typed value; the type must be at least as wide as the entry.
    pub fn get<T: PdoValue>(&self, payload: &[u8], i: usize) -> Result<T, ValueError> {
        let (_, bits) = self.slot(i)?;
        if bits > T::BITS {
            return Err(ValueError::Overflow {
                parameter: "PDO entry wider than the requested type",
            });
        }
        Ok(T::from_raw(self.get_raw(payload, i)?, bits))
    }

    /// Every entry's raw bits.
    pub fn decode(&self, payload: &[u8]) -> Result<[u64; N], ValueError> {
        let word = self.check_len(payload)?;
        let mut out = [0u64; N];
        for (i, slot) in out.iter_mut().enumerate() {
            *slot = (word >> self.offsets[i]) & mask(self.entries[i].bits);
        }
        Ok(out)
    }

    /// Packs raw values (one per entry) into a payload of [`len`](Self::len) bytes. A value
    /// with bits beyond its entry's width is rejected rather than truncated.
    pub fn encode(&self, values: &[u64; N]) -> Result<[u8; 8], ValueError> {
        let mut word = 0u64;
        for (i, value) in values.iter().enumerate() {
            let bits = self.entries[i].bits;
            if value & !mask(bits) != 0 {
                return Err(ValueError::Overflow {
                    parameter: "PDO entry value",
                });
            }
            word |= value << self.offsets[i];
        }
        Ok(word.to_le_bytes())
    }

    /// Sets entry `i` of `payload` to a typed value, keeping the other entries.
    pub fn set<T: PdoValue>(
        &self,
        payload: &mut [u8; 8],
        i: usize,
        value: T,
    ) -> Result<(), ValueError> {
        let (offset, bits) = self.slot(i)?;
        let raw = value.to_raw();
        // Signed values keep their sign bits above the entry width; those must all agree.
        let high = raw & !mask(bits);
        let sign_extended = bits < 64 && high == !mask(bits) && (raw >> (bits - 1)) & 1 == 1;
        if high != 0 && !sign_extended {
            return Err(ValueError::Overflow {
                parameter: "PDO entry value",
            });
        }
        let mut word = u64::from_le_bytes(*payload);
        word &= !(mask(bits) << offset);
        word |= (raw & mask(bits)) << offset;
        *payload = word.to_le_bytes();
        Ok(())
    }
}

/// Entry `i` of `payload` as parameter `P`'s engineering value, through its fixed scale.
/// Generated PDO structs decode their fields with this.
pub fn decode_entry<P: Parameter, const N: usize>(
    layout: &PdoLayout<N>,
    payload: &[u8],
    i: usize,
) -> Result<P::Value, ValueError>
where
    P::Raw: PdoValue,
{
    P::decode(layout.get(payload, i)?, P::SCALE)
}

/// Sets entry `i` of `payload` to parameter `P`'s engineering value, refusing what the
/// parameter's range or the entry's width would not hold.
pub fn encode_entry<P: Parameter, const N: usize>(
    layout: &PdoLayout<N>,
    payload: &mut [u8; 8],
    i: usize,
    value: P::Value,
) -> Result<(), ValueError>
where
    P::Raw: PdoValue,
{
    let raw = P::encode(value, P::SCALE)?;
    P::check(&raw)?;
    layout.set(payload, i, raw)
}

/// The bytes of one PDO: up to 8, as many as its mapping covers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Payload {
    bytes: [u8; 8],
    len: u8,
}

impl Payload {
    /// The first `len` bytes of `bytes` (at most 8).
    pub const fn new(bytes: [u8; 8], len: usize) -> Self {
        Self {
            bytes,
            len: if len > 8 { 8 } else { len as u8 },
        }
    }

    /// The payload, ready for a CAN frame.
    pub fn as_bytes(&self) -> &[u8] {
        &self.bytes[..usize::from(self.len)]
    }
}

const fn mask(bits: u8) -> u64 {
    if bits >= 64 {
        u64::MAX
    } else {
        (1u64 << bits) - 1
    }
}

/// A PDO configuration to apply over SDO.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PdoConfig<'a> {
    /// RPDO or TPDO.
    pub kind: PdoKind,
    /// PDO number, 1..=512.
    pub number: u16,
    /// COB-ID value without the "invalid" bit 31 (bit 30 = no RTR allowed may be set).
    pub cob_id: u32,
    /// Transmission type (sub 2), if it is to be written.
    pub transmission_type: Option<u8>,
    /// Inhibit time (sub 3, in 100 µs), if it is to be written.
    pub inhibit_time: Option<u16>,
    /// Event timer (sub 5, in ms), if it is to be written.
    pub event_timer: Option<u16>,
    /// The mapping.
    pub entries: &'a [MappedObject],
}

/// One SDO download of a plan.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SdoWrite {
    /// Object index.
    pub index: u16,
    /// Subindex.
    pub subindex: u8,
    value: [u8; 4],
    len: u8,
}

impl SdoWrite {
    pub(crate) fn u8(index: u16, subindex: u8, value: u8) -> Self {
        Self {
            index,
            subindex,
            value: [value, 0, 0, 0],
            len: 1,
        }
    }
    pub(crate) fn u16(index: u16, subindex: u8, value: u16) -> Self {
        let [lo, hi] = value.to_le_bytes();
        Self {
            index,
            subindex,
            value: [lo, hi, 0, 0],
            len: 2,
        }
    }
    pub(crate) fn u32(index: u16, subindex: u8, value: u32) -> Self {
        Self {
            index,
            subindex,
            value: value.to_le_bytes(),
            len: 4,
        }
    }
    /// A write of 1, 2 or 4 little-endian bytes; `None` for another length.
    #[cfg(feature = "srdo")]
    pub(crate) fn from_le_bytes(index: u16, subindex: u8, bytes: &[u8]) -> Option<Self> {
        match *bytes {
            [b] => Some(Self::u8(index, subindex, b)),
            [lo, hi] => Some(Self::u16(index, subindex, u16::from_le_bytes([lo, hi]))),
            [a, b, c, d] => Some(Self::u32(index, subindex, u32::from_le_bytes([a, b, c, d]))),
            _ => None,
        }
    }
    /// The little-endian bytes to download.
    pub fn data(&self) -> &[u8] {
        &self.value[..self.len as usize]
    }
}

/// Bit 31 of a PDO COB-ID: the PDO does not exist / is not valid.
pub const COB_ID_INVALID: u32 = 0x8000_0000;

impl<'a> PdoConfig<'a> {
    /// Communication parameter object (0x1400 + n − 1 or 0x1800 + n − 1).
    pub const fn communication_index(&self) -> u16 {
        match self.kind {
            PdoKind::Receive => 0x1400 + self.number - 1,
            PdoKind::Transmit => 0x1800 + self.number - 1,
        }
    }

    /// Mapping parameter object (0x1600 + n − 1 or 0x1A00 + n − 1).
    pub const fn mapping_index(&self) -> u16 {
        match self.kind {
            PdoKind::Receive => 0x1600 + self.number - 1,
            PdoKind::Transmit => 0x1A00 + self.number - 1,
        }
    }

    /// The writes that apply this configuration, in the order CiA 301 requires: disable the
    /// PDO, (set the transmission type, the inhibit time, the event timer: each only while the
    /// PDO is invalid,) zero the entry count, write the entries, set the count, enable the PDO.
    pub fn plan(&self) -> Result<PdoPlan<'a>, BusError> {
        if !(1..=512).contains(&self.number) {
            return Err(BusError::Unsupported("PDO number outside 1..=512"));
        }
        if !mapping_fits(self.entries) {
            return Err(BusError::Unsupported("PDO mapping does not fit 8 bytes"));
        }
        Ok(PdoPlan {
            config: *self,
            step: 0,
        })
    }

    /// Applies the configuration to `node` over `bus`, stopping at the first refused write.
    pub fn apply<B: SdoBus + ?Sized>(&self, bus: &mut B, node: NodeId) -> Result<(), BusError> {
        for write in self.plan()? {
            bus.download(node, write.index, write.subindex, write.data())?;
        }
        Ok(())
    }

    /// [`Self::apply`] over an async SDO client (feature `async`): the same [`Self::plan`],
    /// each write awaited.
    #[cfg(feature = "async")]
    pub async fn apply_async<B: super::link::AsyncSdoBus + ?Sized>(
        &self,
        bus: &mut B,
        node: NodeId,
    ) -> Result<(), BusError> {
        for write in self.plan()? {
            bus.download(node, write.index, write.subindex, write.data())
                .await?;
        }
        Ok(())
    }
}

#[cfg(feature = "std")]
impl<'a> From<&'a PdoSetup> for PdoConfig<'a> {
    /// The configuration of an owned [`PdoSetup`] (a network boot's).
    fn from(setup: &'a PdoSetup) -> Self {
        Self {
            kind: setup.kind,
            number: setup.number,
            cob_id: setup.cob_id,
            transmission_type: setup.transmission_type,
            inhibit_time: setup.inhibit_time,
            event_timer: setup.event_timer,
            entries: &setup.entries,
        }
    }
}

/// The SDO writes of a [`PdoConfig`], in order.
#[derive(Debug, Clone)]
pub struct PdoPlan<'a> {
    config: PdoConfig<'a>,
    step: usize,
}

impl Iterator for PdoPlan<'_> {
    type Item = SdoWrite;

    fn next(&mut self) -> Option<SdoWrite> {
        let c = &self.config;
        let (comm, map, n) = (c.communication_index(), c.mapping_index(), c.entries.len());
        let cob_id = c.cob_id & !COB_ID_INVALID;
        // Steps: disable, transmission type, inhibit time, event timer, zero count, n entries,
        // count, enable.
        let write = match self.step {
            0 => Some(SdoWrite::u32(comm, 1, cob_id | COB_ID_INVALID)),
            1 => c.transmission_type.map(|t| SdoWrite::u8(comm, 2, t)),
            2 => c.inhibit_time.map(|t| SdoWrite::u16(comm, 3, t)),
            3 => c.event_timer.map(|t| SdoWrite::u16(comm, 5, t)),
            4 => Some(SdoWrite::u8(map, 0, 0)),
            s if s < 5 + n => Some(SdoWrite::u32(map, (s - 4) as u8, c.entries[s - 5].entry())),
            s if s == 5 + n => Some(SdoWrite::u8(map, 0, n as u8)),
            s if s == 6 + n => Some(SdoWrite::u32(comm, 1, cob_id)),
            _ => return None,
        };
        self.step += 1;
        match write {
            Some(write) => Some(write),
            None => self.next(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::vec;
    use std::vec::Vec;

    const LAYOUT: PdoLayout<4> = PdoLayout::new([
        MappedObject::new(0x6041, 0, 16),
        MappedObject::new(0x2000, 1, 1),
        MappedObject::new(0x2000, 2, 24),
        MappedObject::new(0x6061, 0, 8),
    ]);
    // Compile-time check, as generated code does it.
    const _: () = assert!(mapping_fits(LAYOUT.entries()));

    #[test]
    fn bit_packed_entries_round_trip_with_sign_extension() {
        let mut payload = [0u8; 8];
        LAYOUT.set(&mut payload, 0, 0x1237u16).unwrap();
        LAYOUT.set(&mut payload, 1, true).unwrap();
        LAYOUT.set(&mut payload, 2, -2i32).unwrap();
        LAYOUT.set(&mut payload, 3, -1i8).unwrap();
        assert_eq!(LAYOUT.len(), 7);
        assert_eq!(LAYOUT.get::<u16>(&payload, 0), Ok(0x1237));
        assert_eq!(LAYOUT.get::<bool>(&payload, 1), Ok(true));
        assert_eq!(LAYOUT.get::<i32>(&payload, 2), Ok(-2));
        assert_eq!(LAYOUT.get::<i8>(&payload, 3), Ok(-1));
        assert_eq!(LAYOUT.get::<u32>(&payload, 2), Ok(0xFF_FFFE));
        let raw = LAYOUT.decode(&payload).unwrap();
        assert_eq!(LAYOUT.encode(&raw).unwrap(), payload);
        // Bit 16 is the flag; the 24-bit value starts at bit 17.
        assert_eq!(payload[..3], [0x37, 0x12, 0b1111_1101]);
    }

    #[test]
    fn bad_payloads_and_values_are_typed_errors() {
        assert_eq!(
            LAYOUT.get::<u16>(&[0; 3], 0),
            Err(ValueError::WrongLength {
                expected: 7,
                actual: 3
            })
        );
        assert!(matches!(
            LAYOUT.get::<u8>(&[0; 7], 0),
            Err(ValueError::Overflow { .. })
        ));
        assert!(matches!(
            LAYOUT.get::<u8>(&[0; 7], 9),
            Err(ValueError::Overflow { .. })
        ));
        let mut payload = [0u8; 8];
        assert!(LAYOUT.set(&mut payload, 2, 0x0100_0000u32).is_err());
        assert!(LAYOUT.set(&mut payload, 2, -0x80_0001i32).is_err());
        assert!(LAYOUT.encode(&[0, 2, 0, 0]).is_err());
    }

    #[test]
    fn fit_check() {
        let eight = [MappedObject::new(0x6040, 0, 8); 8];
        assert!(mapping_fits(&eight));
        assert!(!mapping_fits(&[MappedObject::new(0x6040, 0, 8); 9]));
        assert!(!mapping_fits(&[MappedObject::new(0x6040, 0, 0)]));
        assert_eq!(
            MappedObject::from_entry(0x6041_0010),
            MappedObject::new(0x6041, 0, 16)
        );
    }

    #[test]
    fn configuration_plan_order() {
        let entries = [
            MappedObject::new(0x6041, 0, 16),
            MappedObject::new(0x6064, 0, 32),
        ];
        let config = PdoConfig {
            kind: PdoKind::Transmit,
            number: 1,
            cob_id: 0x181,
            transmission_type: Some(1),
            inhibit_time: None,
            event_timer: None,
            entries: &entries,
        };
        let plan: Vec<(u16, u8, Vec<u8>)> = config
            .plan()
            .unwrap()
            .map(|w| (w.index, w.subindex, w.data().to_vec()))
            .collect();
        assert_eq!(
            plan,
            [
                (0x1800, 1, 0x8000_0181u32.to_le_bytes().to_vec()),
                (0x1800, 2, vec![1]),
                (0x1A00, 0, vec![0]),
                (0x1A00, 1, 0x6041_0010u32.to_le_bytes().to_vec()),
                (0x1A00, 2, 0x6064_0020u32.to_le_bytes().to_vec()),
                (0x1A00, 0, vec![2]),
                (0x1800, 1, 0x181u32.to_le_bytes().to_vec()),
            ]
        );
        let rpdo = PdoConfig {
            kind: PdoKind::Receive,
            number: 3,
            transmission_type: None,
            ..config
        };
        assert_eq!(rpdo.plan().unwrap().count(), 6);
        assert_eq!(
            (rpdo.communication_index(), rpdo.mapping_index()),
            (0x1402, 0x1602)
        );
        assert!(PdoConfig {
            number: 0,
            ..config
        }
        .plan()
        .is_err());
    }

    #[test]
    fn inhibit_time_and_event_timer_are_written_while_the_pdo_is_invalid() {
        let entries = [MappedObject::new(0x6041, 0, 16)];
        let config = PdoConfig {
            kind: PdoKind::Transmit,
            number: 3,
            cob_id: 0x390,
            transmission_type: Some(0xFF),
            inhibit_time: Some(100),
            event_timer: Some(0x01F4),
            entries: &entries,
        };
        let plan: Vec<(u16, u8, Vec<u8>)> = config
            .plan()
            .unwrap()
            .map(|w| (w.index, w.subindex, w.data().to_vec()))
            .collect();
        assert_eq!(
            plan,
            [
                (0x1802, 1, 0x8000_0390u32.to_le_bytes().to_vec()),
                (0x1802, 2, vec![0xFF]),
                (0x1802, 3, vec![100, 0]),
                (0x1802, 5, vec![0xF4, 0x01]),
                (0x1A02, 0, vec![0]),
                (0x1A02, 1, 0x6041_0010u32.to_le_bytes().to_vec()),
                (0x1A02, 0, vec![1]),
                (0x1802, 1, 0x390u32.to_le_bytes().to_vec()),
            ]
        );
        let event_timer_only = PdoConfig {
            inhibit_time: None,
            ..config
        };
        let subs: Vec<u8> = event_timer_only
            .plan()
            .unwrap()
            .filter(|w| w.index == 0x1802)
            .map(|w| w.subindex)
            .collect();
        assert_eq!(subs, [1, 2, 5, 1]);
    }

    #[test]
    fn apply_writes_through_any_sdo_bus_and_stops_on_refusal() {
        use crate::testing::{MemoryBus, Request};
        let entries = [MappedObject::new(0x6041, 0, 16)];
        let config = PdoConfig {
            kind: PdoKind::Receive,
            number: 1,
            cob_id: 0x201,
            transmission_type: None,
            inhibit_time: None,
            event_timer: None,
            entries: &entries,
        };
        let mut bus = MemoryBus::new();
        bus.set_object(0x1400, 1, &[0; 4])
            .set_object(0x1600, 0, &[0])
            .set_object(0x1600, 1, &[0; 4]);
        config.apply(&mut bus, NodeId(1)).unwrap();
        assert_eq!(
            bus.object(0x1600, 1),
            Some(&0x6041_0010u32.to_le_bytes()[..])
        );
        assert_eq!(bus.object(0x1400, 1), Some(&0x201u32.to_le_bytes()[..]));
        let mut empty = MemoryBus::new();
        assert!(config.apply(&mut empty, NodeId(1)).is_err());
        assert_eq!(empty.log().len(), 1);
        assert!(matches!(empty.log()[0], Request::Download(0x1400, 1, _)));
    }
}
