//! Value codecs: how a parameter's raw wire value becomes the value users read and write.
//!
//! A generated parameter names its codec (`type Codec = drivebus::codec::InUnit;`) instead of
//! spelling out `decode` / `encode` bodies, which keeps generated crates small and the conversions
//! written once, here.

use crate::error::ValueError;
use crate::parameter::{FromWire, OpenEnum};
use crate::scale::Scale;
use crate::units::Quantity;
use crate::value::{scale_refusal, Numeric};

/// Converts between raw type `R` and engineering type `V`.
pub trait Codec<R, V> {
    /// Raw → engineering value.
    fn decode(raw: R, scale: Scale) -> Result<V, ValueError>;
    /// Engineering → raw value for `parameter`; fails instead of rounding or truncating.
    fn encode(parameter: &'static str, value: V, scale: Scale) -> Result<R, ValueError>;
}

/// The raw value itself, unscaled.
#[derive(Debug, Clone, Copy)]
pub struct Plain;

impl<R> Codec<R, R> for Plain {
    #[inline]
    fn decode(raw: R, _: Scale) -> Result<R, ValueError> {
        Ok(raw)
    }
    #[inline]
    fn encode(_: &'static str, value: R, _: Scale) -> Result<R, ValueError> {
        Ok(value)
    }
}

/// The scaled value as a bare `f64`, for scaled parameters without a unit.
#[derive(Debug, Clone, Copy)]
pub struct Scaled;

impl<R: Numeric> Codec<R, f64> for Scaled {
    #[inline]
    fn decode(raw: R, scale: Scale) -> Result<f64, ValueError> {
        Ok(scale.to_engineering(raw))
    }
    #[inline]
    fn encode(parameter: &'static str, value: f64, scale: Scale) -> Result<R, ValueError> {
        scale
            .to_raw(value)
            .map_err(|e| scale_refusal(parameter, value, e))
    }
}

/// The scaled value in a unit newtype.
#[derive(Debug, Clone, Copy)]
pub struct InUnit;

impl<R: Numeric, Q: Quantity> Codec<R, Q> for InUnit {
    #[inline]
    fn decode(raw: R, scale: Scale) -> Result<Q, ValueError> {
        Ok(Q::new(scale.to_engineering(raw)))
    }
    #[inline]
    fn encode(parameter: &'static str, value: Q, scale: Scale) -> Result<R, ValueError> {
        let value = value.get();
        scale
            .to_raw(value)
            .map_err(|e| scale_refusal(parameter, value, e))
    }
}

/// An open enumeration: every raw value decodes, documented or not.
#[derive(Debug, Clone, Copy)]
pub struct Enumerated;

impl<E: OpenEnum> Codec<E::Raw, E> for Enumerated {
    #[inline]
    fn decode(raw: E::Raw, _: Scale) -> Result<E, ValueError> {
        Ok(E::from_raw(raw, FromWire(())))
    }
    #[inline]
    fn encode(_: &'static str, value: E, _: Scale) -> Result<E::Raw, ValueError> {
        Ok(value.raw())
    }
}

/// A bit-flags word: every bit survives a read, named or not.
#[derive(Debug, Clone, Copy)]
pub struct Flags;

impl<F: bitflags::Flags> Codec<F::Bits, F> for Flags {
    #[inline]
    fn decode(raw: F::Bits, _: Scale) -> Result<F, ValueError> {
        Ok(F::from_bits_retain(raw))
    }
    #[inline]
    fn encode(_: &'static str, value: F, _: Scale) -> Result<F::Bits, ValueError> {
        Ok(value.bits())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::units::Volts;

    #[test]
    fn in_unit_scales_both_ways() {
        let scale = Scale::fixed(1, 100, 0, 1);
        let v: Volts = InUnit::decode(4950u16, scale).unwrap();
        assert_eq!(v, Volts(49.5));
        let raw: u16 = InUnit::encode("bus_dc_link", Volts(49.5), scale).unwrap();
        assert_eq!(raw, 4950);
        let off_step = <InUnit as Codec<u16, Volts>>::encode("bus_dc_link", Volts(49.505), scale);
        assert!(off_step.is_err(), "{off_step:?}");
    }

    #[test]
    fn scaled_and_plain_round_trip() {
        let scale = Scale::fixed(1, 10, 0, 1);
        let v: f64 = Scaled::decode(-355i16, scale).unwrap();
        assert_eq!(v, -35.5);
        assert_eq!(<Scaled as Codec<i16, f64>>::encode("t", v, scale), Ok(-355));
        assert_eq!(<Plain as Codec<u8, u8>>::decode(7, Scale::IDENTITY), Ok(7));
    }

    bitflags::bitflags! {
        #[derive(Debug, Clone, Copy, PartialEq, Eq)]
        struct Word: u16 {
            const READY = 1;
        }
    }

    #[test]
    fn flags_keep_unnamed_bits() {
        let w: Word = Flags::decode(0x8001u16, Scale::IDENTITY).unwrap();
        assert!(w.contains(Word::READY));
        assert_eq!(
            <Flags as Codec<u16, Word>>::encode("w", w, Scale::IDENTITY),
            Ok(0x8001)
        );
    }
}
