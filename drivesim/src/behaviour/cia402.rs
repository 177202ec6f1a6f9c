//! The CiA 402 power state machine on controlword (6040h) and statusword (6041h), with the mode
//! display (6061h) mirroring the requested mode (6060h). Chosen when the description has both
//! 6040h and 6041h. The velocity setpoint followed in OPERATION ENABLED is 60FFh, or the vl
//! target velocity 6042h on a drive without 60FFh (velocity mode only, e.g. the ez-Wheel SWD).

use std::time::Duration;

use super::{object, Behaviour, Motion, Shared};
use crate::store::{ParamId, Store};

/// CiA 402 power states.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum State {
    /// Switch on disabled.
    SwitchOnDisabled,
    /// Ready to switch on.
    ReadyToSwitchOn,
    /// Switched on.
    SwitchedOn,
    /// Operation enabled.
    OperationEnabled,
    /// Quick stop active.
    QuickStopActive,
    /// Fault.
    Fault,
}

impl State {
    /// The statusword bits (0-6) of the state, CiA 402 Table 30; bit 4 (voltage enabled) is set
    /// whenever the power stage is on.
    pub fn statusword(self) -> u16 {
        match self {
            State::SwitchOnDisabled => 0x0040,
            State::ReadyToSwitchOn => 0x0021,
            State::SwitchedOn => 0x0033,
            State::OperationEnabled => 0x0037,
            State::QuickStopActive => 0x0017,
            State::Fault => 0x0008,
        }
    }

    /// The state a controlword leads to from `self`; `fault_reset` is the rising edge of bit 7.
    pub fn next(self, controlword: u16, fault_reset: bool) -> State {
        use State::*;
        let command = controlword & 0x000F;
        let disable_voltage = command & 0x2 == 0;
        let quick_stop = command & 0x6 == 0x2;
        let shutdown = command & 0x7 == 0x6;
        let switch_on = command == 0x7;
        let enable = command == 0xF;
        match self {
            Fault if fault_reset => SwitchOnDisabled,
            Fault => Fault,
            _ if disable_voltage => SwitchOnDisabled,
            OperationEnabled if quick_stop => QuickStopActive,
            _ if quick_stop => SwitchOnDisabled,
            _ if shutdown => ReadyToSwitchOn,
            SwitchOnDisabled => SwitchOnDisabled,
            ReadyToSwitchOn if switch_on => SwitchedOn,
            ReadyToSwitchOn | SwitchedOn | QuickStopActive if enable => OperationEnabled,
            OperationEnabled if switch_on => SwitchedOn,
            state => state,
        }
    }
}

/// The CiA 402 state machine of one axis.
#[derive(Debug)]
pub struct Cia402 {
    controlword: ParamId,
    statusword: ParamId,
    modes: Option<(ParamId, ParamId)>,
    target_velocity: Option<ParamId>,
    state: State,
    last_controlword: u16,
}

impl Cia402 {
    /// Present when the description has 6040h and 6041h; starts in SWITCH ON DISABLED (the
    /// automatic transitions 0 and 1 after power-on).
    pub fn detect(store: &mut Store) -> Option<Self> {
        let mut machine = Self {
            controlword: object(store, 0x6040, 0)?,
            statusword: object(store, 0x6041, 0)?,
            modes: object(store, 0x6060, 0).zip(object(store, 0x6061, 0)),
            target_velocity: object(store, 0x60FF, 0).or_else(|| object(store, 0x6042, 0)),
            state: State::SwitchOnDisabled,
            last_controlword: 0,
        };
        machine.enter(store, State::SwitchOnDisabled);
        Some(machine)
    }

    fn enter(&mut self, store: &mut Store, state: State) {
        self.state = state;
        store.set_int(self.statusword, i128::from(state.statusword()));
    }

    fn motion(&self) -> Motion {
        match (self.state, self.target_velocity) {
            (State::OperationEnabled, Some(target)) => Motion::Following(target),
            (State::QuickStopActive | State::Fault, _) => Motion::QuickStop,
            _ => Motion::Disabled,
        }
    }
}

impl Behaviour for Cia402 {
    fn written(&mut self, store: &mut Store, shared: &mut Shared, id: ParamId) {
        if let Some((mode, display)) = self.modes.filter(|(mode, _)| *mode == id) {
            let value = store.int(mode).unwrap_or(0);
            store.set_int(display, value);
        }
        if id != self.controlword {
            return;
        }
        let word = store.int(id).unwrap_or(0) as u16;
        let fault_reset = word & 0x80 != 0 && self.last_controlword & 0x80 == 0;
        self.last_controlword = word;
        if fault_reset {
            shared.fault = None;
        }
        let next = self.state.next(word, fault_reset);
        self.enter(store, next);
        shared.motion = self.motion();
    }

    fn tick(&mut self, store: &mut Store, shared: &mut Shared, _dt: Duration) {
        if shared.fault.is_some() && self.state != State::Fault {
            self.enter(store, State::Fault);
            shared.motion = self.motion();
        }
    }

    fn reset(&mut self, store: &mut Store, shared: &mut Shared) {
        self.last_controlword = 0;
        self.enter(store, State::SwitchOnDisabled);
        shared.motion = self.motion();
    }
}

#[cfg(test)]
mod tests {
    use super::State::*;

    #[test]
    fn the_usual_path_reaches_operation_enabled() {
        let ready = SwitchOnDisabled.next(0x06, false);
        assert_eq!(ready, ReadyToSwitchOn);
        let on = ready.next(0x07, false);
        assert_eq!(on, SwitchedOn);
        assert_eq!(on.next(0x0F, false), OperationEnabled);
    }

    #[test]
    fn quick_stop_and_fault_reset() {
        assert_eq!(OperationEnabled.next(0x02, false), QuickStopActive);
        assert_eq!(SwitchedOn.next(0x02, false), SwitchOnDisabled);
        assert_eq!(Fault.next(0x0F, false), Fault);
        assert_eq!(Fault.next(0x80, true), SwitchOnDisabled);
    }

    #[test]
    fn statuswords_match_the_masks_masters_check() {
        // (mask, value) pairs used by CiA 402 masters, e.g. python canopen's BaseNode402.
        assert_eq!(SwitchOnDisabled.statusword() & 0x4F, 0x40);
        assert_eq!(ReadyToSwitchOn.statusword() & 0x6F, 0x21);
        assert_eq!(SwitchedOn.statusword() & 0x6F, 0x23);
        assert_eq!(OperationEnabled.statusword() & 0x6F, 0x27);
        assert_eq!(QuickStopActive.statusword() & 0x6F, 0x07);
        assert_eq!(Fault.statusword() & 0x4F, 0x08);
    }
}
