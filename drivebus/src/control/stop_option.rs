//! What the option codes say about a stop: how the drive brakes on a quick stop (605Ah), a halt
//! (605Dh), a shutdown (605Bh), a disable operation (605Ch) and a fault (605Eh), and where a
//! quick stop ends ([`QuickStopEnd`]). Shared by the simulator, which brakes as the code says,
//! and the drivers, which wait for the end state the code gives.
//!
//! The values are CiA 402-2's (the option code objects of the common entries, as the SWD manual
//! quotes them: `002_7f0dd2fb8f792336.txt` section 10.3, lines 2727-2800). The Kinco manual
//! (`003_8cc8f7f4f05b8633.txt` section 8.13, lines 2128-2132) lists fewer values, each with
//! CiA 402's meaning, and one more: 2 for 605Bh and 605Ch, "stop by using quick stop
//! deceleration, then switch off", a value CiA 402 reserves; it is read here as Kinco gives it,
//! since no drive following CiA 402 sends a reserved value. Which values a drive takes is its
//! description's enum (a write of another is refused before it is sent).

/// How a drive brakes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Braking {
    /// Code 0 of 605Ah, 605Bh, 605Ch, 605Eh, "disable drive function": the power stage is
    /// switched off at once and the motor coasts.
    DisableDriveFunction,
    /// The slow down ramp: the deceleration of the mode (6084h profile deceleration in the
    /// profile modes, the setpoint's own ramp in velocity modes).
    SlowDownRamp,
    /// The quick stop ramp (6085h quick stop deceleration).
    QuickStopRamp,
    /// At the current limit: as hard as the drive can (the simulator stops at once).
    CurrentLimit,
    /// At the voltage limit: as hard as the drive can (the simulator stops at once).
    VoltageLimit,
}

impl Braking {
    /// The braking of quick stop option code `code` (605Ah): 0 disable; 1 and 5 slow down ramp;
    /// 2 and 6 quick stop ramp; 3 and 7 current limit; 4 and 8 voltage limit; `None` for a
    /// manufacturer-specific or reserved value.
    pub const fn quick_stop(code: i128) -> Option<Braking> {
        match code {
            0 => Some(Braking::DisableDriveFunction),
            1 | 5 => Some(Braking::SlowDownRamp),
            2 | 6 => Some(Braking::QuickStopRamp),
            3 | 7 => Some(Braking::CurrentLimit),
            4 | 8 => Some(Braking::VoltageLimit),
            _ => None,
        }
    }

    /// The braking of halt option code `code` (605Dh), the drive staying in operation enabled:
    /// 1 slow down ramp, 2 quick stop ramp, 3 current limit, 4 voltage limit (Kinco: 1 "stop by
    /// current ramp", 2 "stop by quick stop deceleration", line 2131).
    pub const fn halt(code: i128) -> Option<Braking> {
        match code {
            1 => Some(Braking::SlowDownRamp),
            2 => Some(Braking::QuickStopRamp),
            3 => Some(Braking::CurrentLimit),
            4 => Some(Braking::VoltageLimit),
            _ => None,
        }
    }

    /// The braking of shutdown or disable operation option code `code` (605Bh: transition 8;
    /// 605Ch: transition 5): 0 disable drive function, 1 slow down ramp then disable, and
    /// Kinco's 2, quick stop ramp then disable (lines 2129-2130; reserved in CiA 402).
    pub const fn switch_off(code: i128) -> Option<Braking> {
        match code {
            0 => Some(Braking::DisableDriveFunction),
            1 => Some(Braking::SlowDownRamp),
            2 => Some(Braking::QuickStopRamp),
            _ => None,
        }
    }

    /// The braking of fault reaction option code `code` (605Eh): 0 disable drive function, 1
    /// slow down ramp, 2 quick stop ramp, 3 current limit, 4 voltage limit.
    pub const fn fault_reaction(code: i128) -> Option<Braking> {
        match code {
            0 => Some(Braking::DisableDriveFunction),
            1 => Some(Braking::SlowDownRamp),
            2 => Some(Braking::QuickStopRamp),
            3 => Some(Braking::CurrentLimit),
            4 => Some(Braking::VoltageLimit),
            _ => None,
        }
    }
}

/// Where a quick stop from operation enabled ends, as the quick stop option code (605Ah) says.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum QuickStopEnd {
    /// Codes 0-4: switch on disabled (code 0 at once, 1-4 by transition 12 once the drive has
    /// stopped).
    SwitchOnDisabled,
    /// Codes 5-8: quick stop active, the drive standing, until a command leaves it.
    QuickStopActive,
    /// A drive without 605Ah, or a manufacturer-specific code: either of the two; the driver
    /// takes the first it sees.
    Either,
}

impl QuickStopEnd {
    /// The end of quick stop option code `code` (605Ah).
    pub const fn of_code(code: i128) -> QuickStopEnd {
        match code {
            0..=4 => QuickStopEnd::SwitchOnDisabled,
            5..=8 => QuickStopEnd::QuickStopActive,
            _ => QuickStopEnd::Either,
        }
    }

    /// The end of the quick stop option code a read of 605Ah returned; [`Either`] when the read
    /// failed (`None`): a quick stop is never held back by a value it only needs to know where
    /// to stop waiting.
    ///
    /// [`Either`]: QuickStopEnd::Either
    pub fn of_read(code: Option<i16>) -> QuickStopEnd {
        code.map_or(QuickStopEnd::Either, |code| {
            QuickStopEnd::of_code(code.into())
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_quick_stop_code_brakes_and_ends_as_cia_402_says() {
        let table = [
            (
                0,
                Braking::DisableDriveFunction,
                QuickStopEnd::SwitchOnDisabled,
            ),
            (1, Braking::SlowDownRamp, QuickStopEnd::SwitchOnDisabled),
            (2, Braking::QuickStopRamp, QuickStopEnd::SwitchOnDisabled),
            (3, Braking::CurrentLimit, QuickStopEnd::SwitchOnDisabled),
            (4, Braking::VoltageLimit, QuickStopEnd::SwitchOnDisabled),
            (5, Braking::SlowDownRamp, QuickStopEnd::QuickStopActive),
            (6, Braking::QuickStopRamp, QuickStopEnd::QuickStopActive),
            (7, Braking::CurrentLimit, QuickStopEnd::QuickStopActive),
            (8, Braking::VoltageLimit, QuickStopEnd::QuickStopActive),
        ];
        for (code, braking, end) in table {
            assert_eq!(Braking::quick_stop(code), Some(braking), "{code}");
            assert_eq!(QuickStopEnd::of_code(code), end, "{code}");
        }
        assert_eq!(Braking::quick_stop(-1), None);
        assert_eq!(QuickStopEnd::of_code(-1), QuickStopEnd::Either);
        assert_eq!(QuickStopEnd::of_code(9), QuickStopEnd::Either);
    }

    #[test]
    fn a_failed_read_of_the_code_accepts_either_end() {
        assert_eq!(
            QuickStopEnd::of_read(Some(6)),
            QuickStopEnd::QuickStopActive
        );
        assert_eq!(
            QuickStopEnd::of_read(Some(2)),
            QuickStopEnd::SwitchOnDisabled
        );
        assert_eq!(QuickStopEnd::of_read(None), QuickStopEnd::Either);
    }

    #[test]
    fn halt_never_disables_and_switch_off_takes_kincos_2() {
        assert_eq!(Braking::halt(0), None);
        assert_eq!(Braking::halt(1), Some(Braking::SlowDownRamp));
        assert_eq!(Braking::halt(2), Some(Braking::QuickStopRamp));
        assert_eq!(Braking::switch_off(2), Some(Braking::QuickStopRamp));
        assert_eq!(Braking::switch_off(3), None);
        assert_eq!(Braking::fault_reaction(4), Some(Braking::VoltageLimit));
    }
}
