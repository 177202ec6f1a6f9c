//! How a drive deviates from plain CiA 402, as declared in its description (`[cia402]` table).

/// One named deviation; the description lists them by [`Quirk::name`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Quirk {
    /// The mode of operation (0x6060) is only accepted while halt (controlword bit 8) is clear.
    ModeChangeNeedsHaltClear,
    /// Enable operation leaves quick stop active (transition 16); without it the driver goes
    /// through switch-on disabled.
    QuickStopToOperationEnabled,
    /// Switch on (transition 3) only succeeds once the statusword reports voltage enabled (bit 4).
    SwitchOnNeedsVoltage,
    /// The drive honours the remote bit (statusword bit 9): commands wait while it is clear.
    HonoursRemote,
    /// The drive reports homing attained by statusword bit 15 (Kinco's `Reference_found`) and
    /// may leave bits 12 (homing attained) and 10 (target reached) clear; homing is taken as
    /// attained when bit 15 rises after the start (seen clear, then set), or as CiA 402 says.
    HomingAttainedBit15,
}

impl Quirk {
    /// Every quirk, in declaration order.
    pub const ALL: [Quirk; 5] = [
        Quirk::ModeChangeNeedsHaltClear,
        Quirk::QuickStopToOperationEnabled,
        Quirk::SwitchOnNeedsVoltage,
        Quirk::HonoursRemote,
        Quirk::HomingAttainedBit15,
    ];

    /// The name a description uses.
    pub const fn name(self) -> &'static str {
        match self {
            Quirk::ModeChangeNeedsHaltClear => "mode-change-needs-halt-clear",
            Quirk::QuickStopToOperationEnabled => "quick-stop-to-operation-enabled",
            Quirk::SwitchOnNeedsVoltage => "switch-on-needs-voltage",
            Quirk::HonoursRemote => "honours-remote",
            Quirk::HomingAttainedBit15 => "homing-attained-bit-15",
        }
    }

    /// The quirk a description names, if it exists.
    pub fn from_name(name: &str) -> Option<Quirk> {
        Quirk::ALL.into_iter().find(|q| q.name() == name)
    }
}

/// The quirks of one drive, read by the planner and the driver.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Quirks {
    /// See [`Quirk::ModeChangeNeedsHaltClear`].
    pub mode_change_needs_halt_clear: bool,
    /// See [`Quirk::QuickStopToOperationEnabled`].
    pub quick_stop_to_operation_enabled: bool,
    /// See [`Quirk::SwitchOnNeedsVoltage`].
    pub switch_on_needs_voltage: bool,
    /// See [`Quirk::HonoursRemote`].
    pub honours_remote: bool,
    /// See [`Quirk::HomingAttainedBit15`].
    pub homing_attained_bit_15: bool,
    /// How long fault reset (controlword bit 7) is held high before it is dropped to re-arm the
    /// edge, in milliseconds; 0 drops it on the next poll.
    pub fault_reset_hold_ms: u32,
}

impl Quirks {
    /// A drive that behaves as CiA 402 says.
    pub const STANDARD: Quirks = Quirks {
        mode_change_needs_halt_clear: false,
        quick_stop_to_operation_enabled: false,
        switch_on_needs_voltage: false,
        honours_remote: false,
        homing_attained_bit_15: false,
        fault_reset_hold_ms: 0,
    };

    /// These quirks with `quirk` added.
    pub const fn with(mut self, quirk: Quirk) -> Quirks {
        match quirk {
            Quirk::ModeChangeNeedsHaltClear => self.mode_change_needs_halt_clear = true,
            Quirk::QuickStopToOperationEnabled => self.quick_stop_to_operation_enabled = true,
            Quirk::SwitchOnNeedsVoltage => self.switch_on_needs_voltage = true,
            Quirk::HonoursRemote => self.honours_remote = true,
            Quirk::HomingAttainedBit15 => self.homing_attained_bit_15 = true,
        }
        self
    }

    /// Whether `quirk` is declared.
    pub const fn has(&self, quirk: Quirk) -> bool {
        match quirk {
            Quirk::ModeChangeNeedsHaltClear => self.mode_change_needs_halt_clear,
            Quirk::QuickStopToOperationEnabled => self.quick_stop_to_operation_enabled,
            Quirk::SwitchOnNeedsVoltage => self.switch_on_needs_voltage,
            Quirk::HonoursRemote => self.honours_remote,
            Quirk::HomingAttainedBit15 => self.homing_attained_bit_15,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_unknown_names_are_rejected() {
        for quirk in Quirk::ALL {
            assert_eq!(Quirk::from_name(quirk.name()), Some(quirk));
        }
        assert_eq!(Quirk::from_name("mode-change-needs-halt"), None);
    }

    #[test]
    fn with_sets_exactly_one_quirk() {
        for quirk in Quirk::ALL {
            let quirks = Quirks::STANDARD.with(quirk);
            for other in Quirk::ALL {
                assert_eq!(quirks.has(other), other == quirk, "{quirk:?} / {other:?}");
            }
        }
    }
}
