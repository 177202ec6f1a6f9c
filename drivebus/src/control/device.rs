//! The device side of CiA 402: a drive double that reacts to controlwords as the standard's
//! command table says (levels of bits 0-3, rising edge of bit 7) and reports its statusword. It is
//! the test double of the planner and of independent masters (python `canopen.BaseNode402`), and
//! a building block for the simulator.

use super::cia402::{State, FAULT_RESET_BIT};

/// A device control command decoded from a controlword (CiA 402 command table).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Command {
    Shutdown,
    SwitchOn,
    EnableOperation,
    DisableVoltage,
    QuickStop,
}

fn decode(controlword: u16) -> Option<Command> {
    match controlword {
        w if w & 0x82 == 0x00 => Some(Command::DisableVoltage),
        w if w & 0x86 == 0x02 => Some(Command::QuickStop),
        w if w & 0x87 == 0x06 => Some(Command::Shutdown),
        w if w & 0x8F == 0x07 => Some(Command::SwitchOn),
        w if w & 0x8F == 0x0F => Some(Command::EnableOperation),
        _ => None,
    }
}

/// A CiA 402 power drive system as a device sees it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Cia402Device {
    state: State,
    controlword: u16,
}

impl Default for Cia402Device {
    fn default() -> Self {
        Self::in_state(State::SwitchOnDisabled)
    }
}

impl Cia402Device {
    /// A device in `state` whose last controlword was 0.
    pub const fn in_state(state: State) -> Self {
        Self {
            state,
            controlword: 0,
        }
    }

    /// The same device, its last controlword set to `controlword` without acting on it.
    pub const fn with_controlword(mut self, controlword: u16) -> Self {
        self.controlword = controlword;
        self
    }

    /// The current state.
    pub const fn state(&self) -> State {
        self.state
    }

    /// The last controlword received.
    pub const fn controlword(&self) -> u16 {
        self.controlword
    }

    /// The statusword: the state's bits, remote (bit 9) always, voltage enabled (bit 4) while the
    /// power stage may be on.
    pub const fn statusword(&self) -> u16 {
        const REMOTE: u16 = 1 << 9;
        REMOTE
            | match self.state {
                State::NotReadyToSwitchOn => 0x0000,
                State::SwitchOnDisabled => 0x0040,
                State::ReadyToSwitchOn => 0x0031,
                State::SwitchedOn => 0x0033,
                State::OperationEnabled => 0x0037,
                State::QuickStopActive => 0x0017,
                State::FaultReactionActive => 0x001F,
                State::Fault => 0x0018,
            }
    }

    /// Receives a controlword and takes the transition it commands, if any.
    pub fn write_controlword(&mut self, controlword: u16) {
        let rising_reset =
            controlword & FAULT_RESET_BIT != 0 && self.controlword & FAULT_RESET_BIT == 0;
        self.controlword = controlword;
        use Command::*;
        use State::*;
        self.state = match (self.state, decode(controlword)) {
            (Fault, _) if rising_reset => SwitchOnDisabled,
            (SwitchOnDisabled, Some(Shutdown)) => ReadyToSwitchOn,
            (ReadyToSwitchOn, Some(SwitchOn | EnableOperation)) => SwitchedOn,
            (ReadyToSwitchOn, Some(DisableVoltage | QuickStop)) => SwitchOnDisabled,
            (SwitchedOn, Some(EnableOperation)) => OperationEnabled,
            (SwitchedOn, Some(Shutdown)) => ReadyToSwitchOn,
            (SwitchedOn, Some(DisableVoltage | QuickStop)) => SwitchOnDisabled,
            (OperationEnabled, Some(SwitchOn)) => SwitchedOn,
            (OperationEnabled, Some(Shutdown)) => ReadyToSwitchOn,
            (OperationEnabled, Some(DisableVoltage)) => SwitchOnDisabled,
            (OperationEnabled, Some(QuickStop)) => QuickStopActive,
            (QuickStopActive, Some(DisableVoltage)) => SwitchOnDisabled,
            (unchanged, _) => unchanged,
        };
    }

    /// A fault occurs (transition 13).
    pub fn raise_fault(&mut self) {
        self.state = State::FaultReactionActive;
    }

    /// Time passes: the automatic transitions 1 and 14 happen.
    pub fn tick(&mut self) {
        self.state = match self.state {
            State::NotReadyToSwitchOn => State::SwitchOnDisabled,
            State::FaultReactionActive => State::Fault,
            other => other,
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn standard_controlwords_take_the_standard_transitions() {
        let mut device = Cia402Device::default();
        for (controlword, state) in [
            (0x06, State::ReadyToSwitchOn),
            (0x07, State::SwitchedOn),
            (0x0F, State::OperationEnabled),
            (0x02, State::QuickStopActive),
            (0x0F, State::QuickStopActive),
            (0x00, State::SwitchOnDisabled),
        ] {
            device.write_controlword(controlword);
            assert_eq!(device.state(), state, "after {controlword:#04x}");
            assert_eq!(State::decode(device.statusword()), Some(state));
        }
    }

    #[test]
    fn fault_reset_needs_a_rising_edge() {
        let mut device = Cia402Device::default();
        device.write_controlword(0x80);
        device.raise_fault();
        device.tick();
        device.write_controlword(0x80);
        assert_eq!(device.state(), State::Fault);
        device.write_controlword(0x00);
        device.write_controlword(0x80);
        assert_eq!(device.state(), State::SwitchOnDisabled);
    }
}
