//! What an LSS slave answers on 7E4h (CiA 305), decoded into typed values. This is the parser
//! for frames a master receives: any frame is accepted as input, and anything that is not a
//! well-formed LSS answer decodes to `None`.

use super::command::IdentityWord;
use super::{ConfigureError, SLAVE_COB};
use crate::canopen::frame::CanFrame;

/// The configure commands a slave confirms with an error code.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Confirmed {
    /// Configure node id (11h).
    NodeId,
    /// Configure bit timing (13h).
    BitTiming,
    /// Store configuration (17h).
    Store,
}

/// An answer of an LSS slave.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Response {
    /// Switch state selective (44h): the addressed slave is in configuration state.
    SwitchSelective,
    /// A configure or store command's confirmation, with the slave's verdict.
    Confirmed(Confirmed, Result<(), ConfigureError>),
    /// One word of the slave's LSS address (5Ah-5Dh).
    Inquired(IdentityWord, u32),
    /// The slave's node id (5Eh); FFh if it has none.
    NodeId(u8),
    /// Identify slave (4Fh): an answer to an identify remote slave range or a Fastscan step.
    IdentifySlave,
    /// Identify non-configured slave (50h).
    IdentifyNonConfigured,
}

impl Response {
    /// The answer in `frame`, if it is one: COB-ID 7E4h, a data frame, and at least the bytes
    /// its command specifier needs (CiA 305 answers are 8 bytes; shorter ones are read as far
    /// as they go).
    pub fn decode(frame: &CanFrame) -> Option<Self> {
        if frame.id() != SLAVE_COB || frame.is_remote() {
            return None;
        }
        let data = frame.data();
        let cs = *data.first()?;
        let word = || Some(u32::from_le_bytes(data.get(1..5)?.try_into().ok()?));
        Some(match cs {
            0x44 => Self::SwitchSelective,
            0x11 | 0x13 | 0x17 => {
                let command = match cs {
                    0x11 => Confirmed::NodeId,
                    0x13 => Confirmed::BitTiming,
                    _ => Confirmed::Store,
                };
                let code = *data.get(1)?;
                let specific = data.get(2).copied().unwrap_or(0);
                Self::Confirmed(command, ConfigureError::check(command, code, specific))
            }
            0x5A..=0x5D => Self::Inquired(IdentityWord::ALL[usize::from(cs - 0x5A)], word()?),
            0x5E => Self::NodeId(*data.get(1)?),
            0x4F => Self::IdentifySlave,
            0x50 => Self::IdentifyNonConfigured,
            _ => return None,
        })
    }

    /// The 8 data bytes a slave sends (for simulators).
    pub fn to_bytes(self) -> [u8; 8] {
        let mut data = [0u8; 8];
        match self {
            Self::SwitchSelective => data[0] = 0x44,
            Self::Confirmed(command, verdict) => {
                data[0] = match command {
                    Confirmed::NodeId => 0x11,
                    Confirmed::BitTiming => 0x13,
                    Confirmed::Store => 0x17,
                };
                if let Err(error) = verdict {
                    let (code, specific) = error.code();
                    data[1] = code;
                    data[2] = specific;
                }
            }
            Self::Inquired(word, value) => {
                data[0] = 0x5A + word.position();
                data[1..5].copy_from_slice(&value.to_le_bytes());
            }
            Self::NodeId(id) => data[..2].copy_from_slice(&[0x5E, id]),
            Self::IdentifySlave => data[0] = 0x4F,
            Self::IdentifyNonConfigured => data[0] = 0x50,
        }
        data
    }

    /// The frame on 7E4h (for simulators).
    pub fn encode(self) -> CanFrame {
        CanFrame::full(SLAVE_COB, self.to_bytes())
    }
}
