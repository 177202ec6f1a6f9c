//! Writes that stop a drive, and the rule that they are never refused before sending.
//!
//! A description declares the values of a parameter that stop, disable or quick-stop the drive
//! (`stops` in a description: the Lenze smd's `stop` command, a CiA 402 controlword without
//! "enable operation", Lafert's stop and standby commands). A client that believes the drive is
//! locked, or not the drive its description covers, or in an unknown configuration, may be
//! wrong; refusing a stop on such a belief could leave a motor running. So such a write always
//! goes out and the drive's own answer is reported: [`Stops::waive`] is the one rule, applied by
//! `drivebus::Device::write_raw` and by the run-time interpreter's write.

/// Raw values that stop the drive: those whose bits under `mask` equal `value`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct StopPattern {
    /// The bits that decide.
    pub mask: u64,
    /// What those bits hold in a stopping value.
    pub value: u64,
}

impl StopPattern {
    /// Whether `raw` (an integer raw value, two's complement for signed types) matches.
    pub const fn matches(&self, raw: i128) -> bool {
        (raw as u64) & self.mask == self.value
    }
}

/// Which writes of a parameter stop the drive.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Stops<'a> {
    /// None (most parameters).
    #[default]
    Never,
    /// Every write: the parameter is a stop command (Lenze smd `stop`).
    Always,
    /// The values matching any of these patterns (a CiA 402 controlword).
    Matching(&'a [StopPattern]),
}

impl Stops<'_> {
    /// Whether writing the raw value `raw` stops the drive.
    pub fn stops(&self, raw: i128) -> bool {
        match self {
            Stops::Never => false,
            Stops::Always => true,
            Stops::Matching(patterns) => patterns.iter().any(|p| p.matches(raw)),
        }
    }

    /// The refusal that stands for a write of `raw`: none when the write stops the drive, which
    /// is never refused client-side, else `refusal`.
    pub fn waive<R>(&self, raw: i128, refusal: Option<R>) -> Option<R> {
        if self.stops(raw) {
            None
        } else {
            refusal
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// CiA 402 controlword values that stop: bit 1 (enable voltage), bit 2 (quick stop, active
    /// low) or bit 3 (enable operation) clear, or bit 8 (halt) set.
    const CIA402: Stops<'static> = Stops::Matching(&[
        StopPattern {
            mask: 0x0002,
            value: 0,
        },
        StopPattern {
            mask: 0x0004,
            value: 0,
        },
        StopPattern {
            mask: 0x0008,
            value: 0,
        },
        StopPattern {
            mask: 0x0100,
            value: 0x0100,
        },
    ]);

    #[test]
    fn cia402_disable_quick_stop_and_halt_stop_enable_operation_does_not() {
        for stopping in [0x0000, 0x0002, 0x0006, 0x0007, 0x000B, 0x010F, 0x0080] {
            assert!(CIA402.stops(stopping), "{stopping:#06x}");
        }
        for running in [0x000F, 0x001F, 0x003F, 0x005F] {
            assert!(!CIA402.stops(running), "{running:#06x}");
        }
    }

    #[test]
    fn a_stop_waives_the_refusal_and_nothing_else_does() {
        assert_eq!(Stops::Always.waive(4, Some("locked")), None);
        assert_eq!(Stops::Never.waive(4, Some("locked")), Some("locked"));
        assert_eq!(CIA402.waive(0x000F, Some("locked")), Some("locked"));
        assert_eq!(CIA402.waive(0x0002, Some("locked")), None);
    }

    #[test]
    fn signed_values_match_in_twos_complement() {
        let minus_one = Stops::Matching(&[StopPattern {
            mask: 0xFFFF,
            value: 0xFFFF,
        }]);
        assert!(minus_one.stops(-1));
        assert!(!minus_one.stops(1));
    }
}
