//! The deliberate write of the SWD's safety settings that no safety-function signature covers:
//! 6643h "STO active SBC" (which braking the STO applies, RW, line 3265) and 6607h "Safety
//! application configuration valid" (RW, non-volatile, line 3488).
//!
//! Both are `safety = true` in the description, so they have a getter and no plain setter; but
//! none of the signature tables of section 11.8 (lines 3633-3860) lists them, so
//! [`Swd::write_safety_function`] refuses them (`NotSigned`) under every function. This is
//! their one write path, as deliberate as the other: NMT Pre-Operational only (signatures and
//! safety configuration are changed there, line 3484), only these two objects, each value
//! range-checked by [`SafetyValue::of`] before anything is sent, written and read back.
//!
//! Braking on STO must be set on a product with an external brake: SBC 3 (the default, internal
//! braking only, line 3298) is not available with an external brake (lines 3280, 4059-4062), and
//! a mode the hardware cannot apply raises EMCY 6020h (line 3304).

use core::fmt;

use drivebus::canopen::nmt::NmtState;
use drivebus::canopen::srdo::{SafetyValue, SafetyWriteError};
use drivebus::canopen::{CanOpenLink, SdoBus};
use drivebus::BusError;

use crate::Swd;

/// The safety settings no signature covers (index, sub-index): 6643h (line 3265) and 6607h
/// (line 3488).
pub const UNSIGNED_SAFETY_SETTINGS: [(u16, u8); 2] = [(0x6643, 0), (0x6607, 0)];

/// Why a safety-setting write did not complete.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum SafetySettingError {
    /// Refused as the safety-function write refuses (not Pre-Operational, writes refused by
    /// the handle) or failed on the bus; see [`SafetyWriteError`].
    Write(SafetyWriteError),
    /// The value is of an object that is not one of [`UNSIGNED_SAFETY_SETTINGS`]: a signed
    /// safety-function parameter goes through [`Swd::write_safety_function`]; nothing was sent.
    NotAnUnsignedSetting {
        /// Object index of the value.
        index: u16,
        /// Sub-index of the value.
        subindex: u8,
    },
    /// The drive accepted the write but reads back another value.
    ReadBack {
        /// Object index.
        index: u16,
        /// Sub-index.
        subindex: u8,
    },
}

impl fmt::Display for SafetySettingError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Write(e) => write!(f, "{e}"),
            Self::NotAnUnsignedSetting { index, subindex } => write!(
                f,
                "{index:#06x}:{subindex} is not an unsigned safety setting (6643h, 6607h); write it through write_safety_function; nothing was sent"
            ),
            Self::ReadBack { index, subindex } => write!(
                f,
                "{index:#06x}:{subindex} reads back another value than the one written"
            ),
        }
    }
}

impl core::error::Error for SafetySettingError {}

impl<B: SdoBus> Swd<CanOpenLink<B>> {
    /// The deliberate write of the unsigned safety settings 6643h and 6607h: refused before any
    /// frame is sent while the handle refuses writes, unless `state` (as the caller knows it)
    /// is NMT Pre-Operational, and unless every value is of one of
    /// [`UNSIGNED_SAFETY_SETTINGS`]; then writes each value and reads it back.
    ///
    /// ```no_run
    /// # use drivebus::canopen::{nmt::NmtState, srdo::SafetyValue};
    /// # fn f<B: drivebus::canopen::SdoBus>(drive: &mut ezwheel_swd::Swd<drivebus::canopen::CanOpenLink<B>>) -> Result<(), Box<dyn std::error::Error>> {
    /// use ezwheel_swd::params::StoActivateSbc;
    /// use ezwheel_swd::types::SafetyCommand;
    /// // An external brake is fitted: brake with it on STO (SBC 2), not with SBC 3.
    /// let sbc2 = SafetyValue::of::<StoActivateSbc, _>(drive.device(), SafetyCommand::SBC_2)?;
    /// drive.write_safety_setting(NmtState::PreOperational, &[sbc2])?;
    /// # Ok(()) }
    /// ```
    pub fn write_safety_setting(
        &mut self,
        state: NmtState,
        values: &[SafetyValue],
    ) -> Result<(), SafetySettingError> {
        if let Some(reason) = self.device().write_refusal() {
            return Err(SafetySettingError::Write(SafetyWriteError::WritesRefused(
                reason,
            )));
        }
        if state != NmtState::PreOperational {
            return Err(SafetySettingError::Write(
                SafetyWriteError::NotPreOperational { state },
            ));
        }
        if let Some((index, subindex)) = values
            .iter()
            .map(SafetyValue::object)
            .find(|object| !UNSIGNED_SAFETY_SETTINGS.contains(object))
        {
            return Err(SafetySettingError::NotAnUnsignedSetting { index, subindex });
        }
        let link = self.device().link_mut();
        let node = link.node();
        let bus = link.bus_mut();
        let failed = |index, subindex| {
            move |cause: BusError| {
                SafetySettingError::Write(SafetyWriteError::Bus {
                    index,
                    subindex,
                    cause,
                })
            }
        };
        for value in values {
            let (index, subindex) = value.object();
            bus.download(node, index, subindex, value.data())
                .map_err(failed(index, subindex))?;
            let mut read = [0u8; 8];
            let len = bus
                .upload(node, index, subindex, &mut read)
                .map_err(failed(index, subindex))?;
            if read.get(..len) != Some(value.data()) {
                return Err(SafetySettingError::ReadBack { index, subindex });
            }
        }
        Ok(())
    }
}
