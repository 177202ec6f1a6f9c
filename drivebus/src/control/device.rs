//! The device side of CiA 402: a drive that takes the transitions of [`TABLE`] that the
//! controlwords it receives command (levels of bits 0-3, rising edge of bit 7) and reports its
//! statusword. It is the simulator's CiA 402 behaviour (drivesim wraps it) and the test double of
//! the planner and of independent masters (python `canopen.BaseNode402`).
//!
//! # The statusword of each state
//!
//! Bits 0-3, 5 and 6 follow the state coding of CiA 402 (the patterns of [`TABLE`]); where the
//! coding leaves bit 5 free (`x`), it is 0, as the SWD manual prints not ready to switch on
//! (0x0000), switch on disabled (0x0040) and fault (0x0008) (`002_7f0dd2fb8f792336.txt` lines
//! 2390-2391, 4158). The bit table is the SWD manual's (lines 2355-2375). The other bits:
//!
//! * bit 4, voltage enabled: set while the high-level power is on, which CiA 402 switches on with
//!   transition 3 and off with transitions 6, 8, 9, 10, 12 and 14 (the transition table as the SWD
//!   manual quotes it, lines 2258-2275). The Lafert guide has the output stage off in ready to
//!   switch on and on in switched on, operation enabled and quick stop active
//!   (`000_ac225e0ba9cf582c.txt` lines 4919-4937); Kinco reports operation enabled as 0x..37
//!   (`003_8cc8f7f4f05b8633.txt` lines 2359, 2498, 2513, 3260, 3274). The SWD (lines 2393-2394,
//!   4161-4163) and Lafert (lines 5368, 5374) manuals print 0x23 / 0x27 / 0x07 without it (their
//!   ERRATA.md);
//! * bit 9, remote: clear, as every statusword the three manuals print shows it, although the
//!   drives process the controlword (SWD: the SDO answer `4B 41 60 00 XX 00 00 00` whose high
//!   byte is 00, lines 4171-4175, and the tables of lines 2390-2394 and 4158-4163; Kinco: 0xC037,
//!   0xD437 at the lines above). CiA 402 sets it while the controlword is processed (key line
//!   2368; each drive's ERRATA.md). A drive that declares the `honours-remote` quirk, the one on
//!   which the planner waits for bit 9, sets it in every state but not ready to switch on, before
//!   transition 1 activates communication (line 2260): [`Cia402Device::with_quirks`];
//! * bit 7 (warning), bit 8 and bits 10-15 (target reached, mode-specific, manufacturer): 0; the
//!   device models no warning, motion or mode (the simulator's positioning axis adds bits 10, 12
//!   and 13 in profile position and homing mode: `drivesim::behaviour::axis`).
//!
//! | state | statusword | with `honours-remote` |
//! |---|---|---|
//! | not ready to switch on | 0x0000 | 0x0000 |
//! | switch on disabled | 0x0040 | 0x0240 |
//! | ready to switch on | 0x0021 | 0x0221 |
//! | switched on | 0x0033 | 0x0233 |
//! | operation enabled | 0x0037 | 0x0237 |
//! | quick stop active | 0x0017 | 0x0217 |
//! | fault reaction active | 0x001F | 0x021F |
//! | fault | 0x0008 | 0x0208 |
//!
//! # Commands
//!
//! A controlword is decoded by the CiA 402 command table (SWD lines 2336-2346) and the command
//! takes the transition of [`TABLE`] it names from the present state. Two rows of that table are
//! not single transitions of [`TABLE`]: quick stop outside operation enabled is transitions 7 and
//! 10, which [`TABLE`] lists under disable voltage; enable operation in ready to switch on is
//! "switch on + enable operation", transition 3 followed at once by 4. Transition 16 and what a
//! quick stop leads to depend on the [`QuickStopOption`].

use super::cia402::{command, State, FAULT_RESET_BIT, REMOTE_BIT, TABLE, VOLTAGE_ENABLED_BIT};
use super::machine::{TransitionDef, TransitionKind};
use super::quirks::Quirks;

/// A device control command decoded from a controlword (CiA 402 command table).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Command {
    Shutdown,
    SwitchOn,
    EnableOperation,
    DisableVoltage,
    QuickStop,
}

impl Command {
    /// The command a controlword encodes (bits 0-3 and 7), `None` for no command of the table.
    const fn decode(controlword: u16) -> Option<Command> {
        match controlword {
            w if w & 0x82 == 0x00 => Some(Command::DisableVoltage),
            w if w & 0x86 == 0x02 => Some(Command::QuickStop),
            w if w & 0x87 == 0x06 => Some(Command::Shutdown),
            w if w & 0x8F == 0x07 => Some(Command::SwitchOn),
            w if w & 0x8F == 0x0F => Some(Command::EnableOperation),
            _ => None,
        }
    }

    /// The value [`TABLE`] lists for the command's transitions.
    const fn value(self) -> u16 {
        match self {
            Command::Shutdown => command::SHUTDOWN,
            Command::SwitchOn => command::SWITCH_ON,
            Command::EnableOperation => command::ENABLE_OPERATION,
            Command::DisableVoltage => command::DISABLE_VOLTAGE,
            Command::QuickStop => command::QUICK_STOP,
        }
    }
}

/// What a quick stop leads to: the quick stop option code (605Ah) as CiA 402 groups its values
/// (SWD manual lines 2271 and 2275; Kinco's values, `003_8cc8f7f4f05b8633.txt` line 2128).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum QuickStopOption {
    /// Code 0, disable drive function: the drive is switched off at once (transitions 11 and 12
    /// together; Kinco: "stop without control").
    SwitchOff,
    /// Codes 1-4: the drive stops, then goes to switch on disabled by itself (transition 12 when
    /// the quick stop function is completed, at the next [`Cia402Device::tick`]).
    StopThenSwitchOff,
    /// Codes 5-8: the drive stops and stays in quick stop active; enable operation resumes
    /// (transition 16).
    StopAndResume,
    /// The drive stops and stays in quick stop active until disable voltage (transition 12): a
    /// drive whose code is unknown (no 605Ah, a manufacturer-specific value) and which does not
    /// declare the `quick-stop-to-operation-enabled` quirk. The planner assumes no more.
    StopAndHold,
}

impl QuickStopOption {
    /// The group of a quick stop option code (605Ah).
    pub const fn from_code(code: i128) -> Self {
        match code {
            0 => QuickStopOption::SwitchOff,
            1..=4 => QuickStopOption::StopThenSwitchOff,
            5..=8 => QuickStopOption::StopAndResume,
            _ => QuickStopOption::StopAndHold,
        }
    }

    /// For a drive without a quick stop option code: the quirk
    /// [`QuickStopToOperationEnabled`](super::quirks::Quirk::QuickStopToOperationEnabled)
    /// declares transition 16; without it the drive holds.
    pub const fn from_quirks(quirks: Quirks) -> Self {
        if quirks.quick_stop_to_operation_enabled {
            QuickStopOption::StopAndResume
        } else {
            QuickStopOption::StopAndHold
        }
    }
}

/// A CiA 402 power drive system as a device sees it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Cia402Device {
    state: State,
    controlword: u16,
    quick_stop: QuickStopOption,
    remote: bool,
}

impl Default for Cia402Device {
    fn default() -> Self {
        Self::in_state(State::SwitchOnDisabled)
    }
}

impl Cia402Device {
    /// A device in `state` whose last controlword was 0, of a drive without quirks: holding in
    /// quick stop active ([`QuickStopOption::StopAndHold`]), remote (bit 9) clear.
    pub const fn in_state(state: State) -> Self {
        Self {
            state,
            controlword: 0,
            quick_stop: QuickStopOption::StopAndHold,
            remote: false,
        }
    }

    /// The same device for a drive with `quirks`: `honours-remote` sets bit 9 while the
    /// controlword is processed; `quick-stop-to-operation-enabled` gives transition 16
    /// ([`QuickStopOption::from_quirks`], until an option code is set).
    pub const fn with_quirks(mut self, quirks: Quirks) -> Self {
        self.remote = quirks.honours_remote;
        self.quick_stop = QuickStopOption::from_quirks(quirks);
        self
    }

    /// The same device, its last controlword set to `controlword` without acting on it.
    pub const fn with_controlword(mut self, controlword: u16) -> Self {
        self.controlword = controlword;
        self
    }

    /// The same device with quick stop option `option`.
    pub const fn with_quick_stop_option(mut self, option: QuickStopOption) -> Self {
        self.quick_stop = option;
        self
    }

    /// Sets what a quick stop leads to from now on (605Ah may be written at run time).
    pub fn set_quick_stop_option(&mut self, option: QuickStopOption) {
        self.quick_stop = option;
    }

    /// The current state.
    pub const fn state(&self) -> State {
        self.state
    }

    /// The last controlword received.
    pub const fn controlword(&self) -> u16 {
        self.controlword
    }

    /// What a quick stop leads to.
    pub const fn quick_stop_option(&self) -> QuickStopOption {
        self.quick_stop
    }

    /// The statusword of the present state (the table in the module documentation).
    pub const fn statusword(&self) -> u16 {
        let processed = !matches!(self.state, State::NotReadyToSwitchOn);
        if self.remote && processed {
            statusword(self.state) | REMOTE_BIT
        } else {
            statusword(self.state)
        }
    }

    /// Receives a controlword and takes the transition it commands, if any; returns the last
    /// transition taken (for "switch on + enable operation", transition 4).
    pub fn write_controlword(
        &mut self,
        controlword: u16,
    ) -> Option<&'static TransitionDef<'static>> {
        let rising_reset =
            controlword & FAULT_RESET_BIT != 0 && self.controlword & FAULT_RESET_BIT == 0;
        self.controlword = controlword;
        if self.state == State::Fault {
            return if rising_reset {
                self.take(command::FAULT_RESET)
            } else {
                None
            };
        }
        let command = Command::decode(controlword)?;
        match (self.state, command) {
            // Quick stop outside operation enabled: transitions 7 and 10 (disable voltage's).
            (State::ReadyToSwitchOn | State::SwitchedOn, Command::QuickStop) => {
                self.take(command::DISABLE_VOLTAGE)
            }
            // Switch on + enable operation: transition 3, then 4 at once.
            (State::ReadyToSwitchOn, Command::EnableOperation) => {
                self.take(command::SWITCH_ON)?;
                self.take(command::ENABLE_OPERATION)
            }
            (State::QuickStopActive, Command::EnableOperation)
                if self.quick_stop != QuickStopOption::StopAndResume =>
            {
                None
            }
            (State::OperationEnabled, Command::QuickStop)
                if self.quick_stop == QuickStopOption::SwitchOff =>
            {
                self.take(command::QUICK_STOP)?;
                self.take(command::DISABLE_VOLTAGE)
            }
            _ => self.take(command.value()),
        }
    }

    /// A fault occurs (transition 13).
    pub fn raise_fault(&mut self) -> Option<&'static TransitionDef<'static>> {
        self.take_kind(TransitionKind::External)
    }

    /// Time passes: the drive takes the transitions it takes by itself (1, 14, and 12 once a quick
    /// stop with [`QuickStopOption::StopThenSwitchOff`] has stopped the drive).
    pub fn tick(&mut self) -> Option<&'static TransitionDef<'static>> {
        match (self.state, self.quick_stop) {
            (State::QuickStopActive, QuickStopOption::StopThenSwitchOff) => {
                self.take(command::DISABLE_VOLTAGE)
            }
            _ => self.take_kind(TransitionKind::Automatic),
        }
    }

    /// Takes the transition of [`TABLE`] that the command `value` causes from the present state.
    fn take(&mut self, value: u16) -> Option<&'static TransitionDef<'static>> {
        self.take_kind(TransitionKind::Command(value))
    }

    fn take_kind(&mut self, kind: TransitionKind) -> Option<&'static TransitionDef<'static>> {
        let from = self.state.index();
        let transition = TABLE
            .transitions
            .iter()
            .find(|t| t.from == from && t.kind == kind)?;
        self.state = *State::ALL.get(usize::from(transition.to))?;
        Some(transition)
    }
}

/// The statusword a device in `state` reports, remote (bit 9) clear (the table in the module
/// documentation).
pub const fn statusword(state: State) -> u16 {
    const QUICK_STOP_BIT: u16 = 1 << 5;
    let coding = match state {
        State::NotReadyToSwitchOn => 0x0000,
        State::SwitchOnDisabled => 0x0040,
        State::ReadyToSwitchOn => 0x0001 | QUICK_STOP_BIT,
        State::SwitchedOn => 0x0003 | QUICK_STOP_BIT,
        State::OperationEnabled => 0x0007 | QUICK_STOP_BIT,
        State::QuickStopActive => 0x0007,
        State::FaultReactionActive => 0x000F,
        State::Fault => 0x0008,
    };
    let voltage = match state {
        State::SwitchedOn
        | State::OperationEnabled
        | State::QuickStopActive
        | State::FaultReactionActive => VOLTAGE_ENABLED_BIT,
        _ => 0,
    };
    coding | voltage
}

#[cfg(test)]
#[path = "device_tests.rs"]
mod tests;
