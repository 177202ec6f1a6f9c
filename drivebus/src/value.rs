//! Raw wire values: how each description data type travels as little-endian bytes.
//!
//! Every protocol binding hands values to the codec as little-endian bytes (CANopen's native order;
//! Modbus links reorder registers first). A value may travel in fewer bytes than its Rust type
//! (24/40/48/56-bit CANopen types) or more (a `u8` in a 16-bit register); the codec sign- or
//! zero-extends and refuses anything that does not fit rather than truncating it.

use crate::error::ValueError;
use crate::interpret::RawValue;
pub use drivebus_model::Scalable;
use drivebus_model::ScaleError;

/// A raw value as it crosses the wire.
pub trait WireValue: Sized + Copy + core::fmt::Debug + PartialEq + 'static {
    /// Natural size in bytes of the type on the wire.
    const WIRE_BYTES: usize;
    /// Decodes from little-endian bytes; `bytes` may be shorter or longer than [`Self::WIRE_BYTES`].
    fn decode_le(bytes: &[u8]) -> Result<Self, ValueError>;
    /// Encodes into exactly `out.len()` little-endian bytes, or fails if the value does not fit.
    fn encode_le(&self, out: &mut [u8]) -> Result<(), ValueError>;
    /// The value as an exact integer, for integer and boolean types (`false` 0, `true` 1):
    /// what bounds set by other parameters compare. `None` for floats and text.
    fn to_int(&self) -> Option<i128> {
        None
    }
}

/// A numeric raw value as it crosses the wire: a [`WireValue`] a [`Scale`](crate::Scale)
/// converts and range checks compare ([`Scalable`]).
pub trait Numeric: WireValue + Scalable {
    /// The value exactly, as errors report it: an integer as an integer (a 64-bit raw value
    /// beyond 2^53 would lose its low bits in an `f64`), a float as a float.
    fn to_raw_value(self) -> RawValue {
        self.to_int()
            .map_or_else(|| RawValue::Float(self.to_f64()), RawValue::Int)
    }
}

impl<T: WireValue + Scalable> Numeric for T {}

/// `value`, refused by `parameter`'s scale, as the value error a write reports.
pub(crate) fn scale_refusal(parameter: &'static str, value: f64, error: ScaleError) -> ValueError {
    match error {
        ScaleError::Overflow => ValueError::Overflow { parameter },
        ScaleError::BetweenSteps { step } => ValueError::NotRepresentable {
            parameter,
            value,
            step,
        },
    }
}

const ERR_OVERFLOW: ValueError = ValueError::Overflow { parameter: "" };

fn wrong_length(expected: usize, actual: usize) -> ValueError {
    ValueError::WrongLength { expected, actual }
}

/// Reads up to 16 little-endian bytes as a sign- or zero-extended integer.
fn int_from_le(bytes: &[u8], signed: bool) -> Result<i128, ValueError> {
    if bytes.is_empty() || bytes.len() > 16 {
        return Err(wrong_length(8, bytes.len()));
    }
    let mut buf = [0u8; 16];
    buf[..bytes.len()].copy_from_slice(bytes);
    let negative = signed && bytes[bytes.len() - 1] & 0x80 != 0;
    if negative {
        buf[bytes.len()..].fill(0xFF);
    }
    Ok(i128::from_le_bytes(buf))
}

/// Writes an integer into `out.len()` little-endian bytes, failing if it does not fit.
fn int_to_le(value: i128, signed: bool, out: &mut [u8]) -> Result<(), ValueError> {
    let bits = out.len() as u32 * 8;
    if out.is_empty() || bits > 128 {
        return Err(wrong_length(8, out.len()));
    }
    let fits = match (signed, bits) {
        (_, 128) => true,
        (true, b) => value >= -(1i128 << (b - 1)) && value < (1i128 << (b - 1)),
        (false, b) => value >= 0 && value < (1i128 << b),
    };
    if !fits {
        return Err(ERR_OVERFLOW);
    }
    out.copy_from_slice(&value.to_le_bytes()[..out.len()]);
    Ok(())
}

macro_rules! integer_wire_value {
    ($($ty:ty => $signed:expr),* $(,)?) => {$(
        impl WireValue for $ty {
            const WIRE_BYTES: usize = core::mem::size_of::<$ty>();
            fn decode_le(bytes: &[u8]) -> Result<Self, ValueError> {
                let wide = int_from_le(bytes, $signed)?;
                <$ty>::try_from(wide).map_err(|_| ERR_OVERFLOW)
            }
            fn encode_le(&self, out: &mut [u8]) -> Result<(), ValueError> {
                int_to_le(*self as i128, $signed, out)
            }
            fn to_int(&self) -> Option<i128> {
                Some(*self as i128)
            }
        }
    )*};
}

integer_wire_value!(
    u8 => false, u16 => false, u32 => false, u64 => false,
    i8 => true, i16 => true, i32 => true, i64 => true,
);

macro_rules! float_wire_value {
    ($($ty:ty),*) => {$(
        impl WireValue for $ty {
            const WIRE_BYTES: usize = core::mem::size_of::<$ty>();
            fn decode_le(bytes: &[u8]) -> Result<Self, ValueError> {
                let array = bytes.try_into().map_err(|_| wrong_length(Self::WIRE_BYTES, bytes.len()))?;
                Ok(<$ty>::from_le_bytes(array))
            }
            fn encode_le(&self, out: &mut [u8]) -> Result<(), ValueError> {
                if out.len() != Self::WIRE_BYTES {
                    return Err(wrong_length(Self::WIRE_BYTES, out.len()));
                }
                out.copy_from_slice(&self.to_le_bytes());
                Ok(())
            }
        }
    )*};
}

float_wire_value!(f32, f64);

impl WireValue for bool {
    const WIRE_BYTES: usize = 1;
    fn decode_le(bytes: &[u8]) -> Result<Self, ValueError> {
        match int_from_le(bytes, false)? {
            0 => Ok(false),
            1 => Ok(true),
            _ => Err(ERR_OVERFLOW),
        }
    }
    fn encode_le(&self, out: &mut [u8]) -> Result<(), ValueError> {
        int_to_le(*self as i128, false, out)
    }
    fn to_int(&self) -> Option<i128> {
        Some(i128::from(*self))
    }
}

/// A fixed-capacity byte string (CANopen VISIBLE_STRING / OCTET_STRING), heap free.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct Text<const N: usize> {
    bytes: [u8; N],
    len: usize,
}

impl<const N: usize> Text<N> {
    /// Builds a text from bytes, or `None` if longer than the capacity `N`.
    pub fn from_bytes(bytes: &[u8]) -> Option<Self> {
        let mut text = Self {
            bytes: [0; N],
            len: bytes.len(),
        };
        text.bytes.get_mut(..bytes.len())?.copy_from_slice(bytes);
        Some(text)
    }
    /// The stored bytes.
    pub fn as_bytes(&self) -> &[u8] {
        &self.bytes[..self.len]
    }
    /// The bytes as UTF-8, if they are.
    pub fn as_str(&self) -> Option<&str> {
        core::str::from_utf8(self.as_bytes()).ok()
    }
}

impl<const N: usize> core::fmt::Debug for Text<N> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self.as_str() {
            Some(s) => write!(f, "{s:?}"),
            None => write!(f, "{:02x?}", self.as_bytes()),
        }
    }
}

impl<const N: usize> WireValue for Text<N> {
    const WIRE_BYTES: usize = N;
    fn decode_le(bytes: &[u8]) -> Result<Self, ValueError> {
        // Devices pad fixed-size strings with NULs; they are not part of the text.
        let end = bytes.iter().position(|&b| b == 0).unwrap_or(bytes.len());
        Self::from_bytes(&bytes[..end]).ok_or(ValueError::BadText)
    }
    fn encode_le(&self, out: &mut [u8]) -> Result<(), ValueError> {
        let target = out.get_mut(..self.len).ok_or(ValueError::BadText)?;
        target.copy_from_slice(self.as_bytes());
        out[self.len..].fill(0);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn short_signed_payload_is_sign_extended() {
        assert_eq!(i32::decode_le(&[0xFE, 0xFF, 0xFF]), Ok(-2));
        assert_eq!(u32::decode_le(&[0xFE, 0xFF, 0xFF]), Ok(0x00FF_FFFE));
    }

    #[test]
    fn long_payload_must_fit_the_type() {
        assert_eq!(u8::decode_le(&[0x12, 0x00]), Ok(0x12));
        assert_eq!(u8::decode_le(&[0x12, 0x01]), Err(ERR_OVERFLOW));
        assert_eq!(i16::decode_le(&[0x48, 0xF4]), Ok(-3000));
    }

    #[test]
    fn encoding_refuses_values_that_do_not_fit_the_wire_width() {
        let mut two = [0u8; 2];
        assert_eq!((-3000i16).encode_le(&mut two), Ok(()));
        assert_eq!(two, [0x48, 0xF4]);
        let mut three = [0u8; 3];
        assert_eq!(0x0100_0000u32.encode_le(&mut three), Err(ERR_OVERFLOW));
        assert_eq!((-1i32).encode_le(&mut three), Ok(()));
        assert_eq!(three, [0xFF; 3]);
    }

    #[test]
    fn floats_refuse_what_their_width_makes_infinite() {
        assert_eq!(f32::from_f64(1e39), None);
        assert_eq!(f32::from_f64(-1e39), None);
        assert_eq!(f32::from_f64(3.0e38), Some(3.0e38));
        assert_eq!(f64::from_f64(f64::INFINITY), None);
        assert_eq!(
            crate::Scale::IDENTITY.to_raw::<f32>(1e39),
            Err(ScaleError::Overflow)
        );
    }

    #[test]
    fn floats_need_their_exact_width() {
        assert_eq!(f32::decode_le(&1.5f32.to_le_bytes()), Ok(1.5));
        assert!(f32::decode_le(&[0, 0]).is_err());
    }

    #[test]
    fn text_strips_padding_and_respects_capacity() {
        let t = Text::<8>::decode_le(b"SWD\0\0").unwrap();
        assert_eq!(t.as_str(), Some("SWD"));
        assert!(Text::<2>::decode_le(b"SWD").is_err());
    }
}
