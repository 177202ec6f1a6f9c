//! Changing the mode of operation: the request goes to 0x6060, the drive confirms it in 0x6061.
//!
//! The modes themselves are the description's open enum (`types::ModesOfOperation` in a generated
//! crate, raw `i8`, negative values manufacturer-specific); this module only decides the order of
//! writes and what counts as confirmed.

use super::cia402::HALT_BIT;
use super::quirks::Quirks;

/// What to write before the mode itself.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ModeStep {
    /// The drive only takes a mode change with halt clear: write this controlword first.
    ClearHaltFirst {
        /// The current controlword with bit 8 cleared.
        controlword: u16,
    },
    /// Write the mode now.
    WriteMode,
}

/// The first step of a mode change, given the controlword currently in force.
pub fn mode_change(quirks: &Quirks, controlword: u16) -> ModeStep {
    if quirks.mode_change_needs_halt_clear && controlword & HALT_BIT != 0 {
        ModeStep::ClearHaltFirst {
            controlword: controlword & !HALT_BIT,
        }
    } else {
        ModeStep::WriteMode
    }
}

/// Whether the mode display (0x6061) confirms the requested mode (0x6060).
pub const fn confirmed(requested: i8, displayed: i8) -> bool {
    requested == displayed
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::control::quirks::Quirk;

    #[test]
    fn halt_is_cleared_first_only_with_the_quirk_and_halt_set() {
        let quirky = Quirks::STANDARD.with(Quirk::ModeChangeNeedsHaltClear);
        assert_eq!(
            mode_change(&quirky, 0x010F),
            ModeStep::ClearHaltFirst {
                controlword: 0x000F
            }
        );
        assert_eq!(mode_change(&quirky, 0x000F), ModeStep::WriteMode);
        assert_eq!(mode_change(&Quirks::STANDARD, 0x010F), ModeStep::WriteMode);
    }

    #[test]
    fn manufacturer_modes_are_confirmed_by_their_own_value() {
        assert!(confirmed(-3, -3));
        assert!(!confirmed(-3, 3));
    }
}
