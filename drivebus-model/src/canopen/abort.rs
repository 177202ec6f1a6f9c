//! The CiA 301 SDO abort codes, typed, with their meanings.

use core::fmt;

macro_rules! abort_codes {
    ($($(#[$doc:meta])* $name:ident = $code:literal, $meaning:literal;)*) => {
        /// An SDO abort code (CiA 301 §7.2.4.3.17). Codes outside the standard table are kept as
        /// [`AbortCode::Other`].
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        #[non_exhaustive]
        pub enum AbortCode {
            $($(#[$doc])* #[doc = $meaning] $name,)*
            /// A manufacturer-specific or unknown code.
            Other(u32),
        }

        impl AbortCode {
            /// Every standard code, in table order.
            pub const ALL: &'static [AbortCode] = &[$(AbortCode::$name,)*];

            /// The typed code for a raw value.
            pub const fn from_u32(code: u32) -> Self {
                match code {
                    $($code => Self::$name,)*
                    other => Self::Other(other),
                }
            }

            /// The raw 32-bit value sent on the bus.
            pub const fn code(self) -> u32 {
                match self {
                    $(Self::$name => $code,)*
                    Self::Other(code) => code,
                }
            }

            /// What the code means, as CiA 301 words it.
            pub const fn meaning(self) -> &'static str {
                match self {
                    $(Self::$name => $meaning,)*
                    Self::Other(_) => "manufacturer-specific or unknown abort code",
                }
            }
        }
    };
}

abort_codes! {
    ToggleBitNotAlternated = 0x0503_0000, "toggle bit not alternated";
    ProtocolTimedOut = 0x0504_0000, "SDO protocol timed out";
    InvalidCommandSpecifier = 0x0504_0001, "client/server command specifier not valid or unknown";
    InvalidBlockSize = 0x0504_0002, "invalid block size (block mode only)";
    InvalidSequenceNumber = 0x0504_0003, "invalid sequence number (block mode only)";
    CrcError = 0x0504_0004, "CRC error (block mode only)";
    OutOfMemory = 0x0504_0005, "out of memory";
    UnsupportedAccess = 0x0601_0000, "unsupported access to an object";
    WriteOnly = 0x0601_0001, "attempt to read a write only object";
    ReadOnly = 0x0601_0002, "attempt to write a read only object";
    ObjectDoesNotExist = 0x0602_0000, "object does not exist in the object dictionary";
    CannotBeMapped = 0x0604_0041, "object cannot be mapped to the PDO";
    PdoLengthExceeded = 0x0604_0042, "the number and length of the objects to be mapped would exceed PDO length";
    ParameterIncompatibility = 0x0604_0043, "general parameter incompatibility reason";
    InternalIncompatibility = 0x0604_0047, "general internal incompatibility in the device";
    HardwareError = 0x0606_0000, "access failed due to a hardware error";
    LengthMismatch = 0x0607_0010, "data type does not match, length of service parameter does not match";
    LengthTooHigh = 0x0607_0012, "data type does not match, length of service parameter too high";
    LengthTooLow = 0x0607_0013, "data type does not match, length of service parameter too low";
    SubindexDoesNotExist = 0x0609_0011, "sub-index does not exist";
    InvalidValue = 0x0609_0030, "invalid value for parameter (download only)";
    ValueTooHigh = 0x0609_0031, "value of parameter written too high (download only)";
    ValueTooLow = 0x0609_0032, "value of parameter written too low (download only)";
    MaxLessThanMin = 0x0609_0036, "maximum value is less than minimum value";
    ResourceNotAvailable = 0x060A_0023, "resource not available: SDO connection";
    GeneralError = 0x0800_0000, "general error";
    CannotStore = 0x0800_0020, "data cannot be transferred or stored to the application";
    CannotStoreLocalControl = 0x0800_0021, "data cannot be transferred or stored to the application because of local control";
    CannotStoreDeviceState = 0x0800_0022, "data cannot be transferred or stored to the application because of the present device state";
    NoObjectDictionary = 0x0800_0023, "object dictionary dynamic generation fails or no object dictionary is present";
    NoDataAvailable = 0x0800_0024, "no data available";
}

impl From<u32> for AbortCode {
    fn from(code: u32) -> Self {
        Self::from_u32(code)
    }
}

impl From<AbortCode> for u32 {
    fn from(code: AbortCode) -> Self {
        code.code()
    }
}

impl fmt::Display for AbortCode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:#010x} ({})", self.code(), self.meaning())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_standard_code_round_trips_and_has_its_own_meaning() {
        assert_eq!(AbortCode::ALL.len(), 31);
        for (i, code) in AbortCode::ALL.iter().enumerate() {
            assert_eq!(AbortCode::from_u32(code.code()), *code);
            assert!(AbortCode::ALL[..i]
                .iter()
                .all(|other| other.meaning() != code.meaning()));
        }
    }

    #[test]
    fn unknown_codes_are_kept_raw() {
        let code = AbortCode::from(0x0800_00FF);
        assert_eq!(code, AbortCode::Other(0x0800_00FF));
        assert_eq!(u32::from(code), 0x0800_00FF);
    }

    #[test]
    fn display_names_code_and_meaning() {
        use std::string::ToString;
        assert_eq!(
            AbortCode::ObjectDoesNotExist.to_string(),
            "0x06020000 (object does not exist in the object dictionary)"
        );
    }
}
