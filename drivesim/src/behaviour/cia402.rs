//! The CiA 402 power state machine on controlword (6040h) and statusword (6041h), with the mode
//! display (6061h) mirroring the requested mode (6060h). Chosen when the description has both
//! 6040h and 6041h. The states, transitions and statuswords are the runtime's device side
//! ([`Cia402Device`]); this behaviour feeds it the controlwords written, the faults raised and
//! the passing of time, and stores its statusword. The velocity setpoint followed in OPERATION
//! ENABLED is 60FFh, or the vl target velocity 6042h on a drive without 60FFh (velocity mode only,
//! e.g. the ez-Wheel SWD).
//!
//! Leaving operation enabled, the motor brakes as the transition's option code says
//! ([`Braking`]; CiA 402-2 605Ah-605Ch, Kinco manual section 8.13 lines 2128-2130): a quick stop
//! (605Ah) on the slow down ramp (the setpoint's own deceleration) or the quick stop ramp
//! (6085h), a shutdown (605Bh) or disable operation (605Ch) likewise; the current and voltage
//! limits, a code the drive leaves undefined and a drive without the object stop at once, as
//! before option codes were read. The statusword shows the new state at once; a quick stop whose
//! code ends in switch on disabled (1-4) stays in quick stop active until the velocity actual
//! value reads 0, then takes transition 12.

use std::time::Duration;

use drivebus::control::device::{Cia402Device, QuickStopOption};
use drivebus::control::stop_option::Braking;
use drivebus::control::{Quirk, Quirks, State};

use super::{object, Behaviour, Motion, Shared};
use crate::store::{ParamId, Store};

/// The CiA 402 state machine of one axis.
#[derive(Debug)]
pub struct Cia402 {
    controlword: ParamId,
    statusword: ParamId,
    modes: Option<(ParamId, ParamId)>,
    target_velocity: Option<ParamId>,
    /// The quick stop option code (605Ah), read at each controlword since it may be written.
    quick_stop_option_code: Option<ParamId>,
    /// The shutdown (605Bh) and disable operation (605Ch) option codes.
    shutdown_option_code: Option<ParamId>,
    disable_operation_option_code: Option<ParamId>,
    /// The quick stop deceleration (6085h), the quick stop ramp.
    quick_stop_deceleration: Option<ParamId>,
    /// The velocity actual values (606Ch, 6044h): the drive has stopped when they read 0.
    velocity_actuals: Vec<ParamId>,
    /// How the drive brakes after leaving operation enabled by transition 5, 8 or 11 (`None`:
    /// at once, the behaviour without option codes).
    braking: Option<Braking>,
    /// The `[cia402]` quirks: remote (bit 9) shown, and transition 16 on a drive without 605Ah.
    quirks: Quirks,
    device: Cia402Device,
}

impl Cia402 {
    /// Present when the description has 6040h and 6041h; starts in SWITCH ON DISABLED (the
    /// automatic transitions 0 and 1 after power-on).
    pub fn detect(store: &mut Store) -> Option<Self> {
        let quirks = declared_quirks(store);
        let machine = Self {
            controlword: object(store, 0x6040, 0)?,
            statusword: object(store, 0x6041, 0)?,
            modes: object(store, 0x6060, 0).zip(object(store, 0x6061, 0)),
            target_velocity: object(store, 0x60FF, 0).or_else(|| object(store, 0x6042, 0)),
            quick_stop_option_code: object(store, 0x605A, 0),
            shutdown_option_code: object(store, 0x605B, 0),
            disable_operation_option_code: object(store, 0x605C, 0),
            quick_stop_deceleration: object(store, 0x6085, 0),
            velocity_actuals: [0x606C, 0x6044]
                .into_iter()
                .filter_map(|index| object(store, index, 0))
                .collect(),
            braking: None,
            quirks,
            device: Cia402Device::default().with_quirks(quirks),
        };
        machine.show(store);
        Some(machine)
    }

    /// What a quick stop leads to now: the option code's group, or the quirks' answer.
    fn quick_stop_option(&self, store: &Store) -> QuickStopOption {
        self.quick_stop_option_code
            .and_then(|id| store.int(id))
            .map_or(
                QuickStopOption::from_quirks(self.quirks),
                QuickStopOption::from_code,
            )
    }

    fn show(&self, store: &mut Store) {
        store.set_int(self.statusword, i128::from(self.device.statusword()));
    }

    /// How the drive brakes after transition `name` out of operation enabled, as the option
    /// code of the transition says (11 quick stop 605Ah, 8 shutdown 605Bh, 5 disable operation
    /// 605Ch); `None` for another transition or without the object.
    fn braking_of(&self, store: &Store, name: &str) -> Option<Braking> {
        let code = |id: Option<ParamId>| id.and_then(|id| store.int(id));
        match name {
            "11" => code(self.quick_stop_option_code).and_then(Braking::quick_stop),
            "8" => code(self.shutdown_option_code).and_then(Braking::switch_off),
            "5" => code(self.disable_operation_option_code).and_then(Braking::switch_off),
            _ => None,
        }
    }

    /// Whether the motor stands (every velocity actual value reads 0).
    fn stopped(&self, store: &Store) -> bool {
        let speed = |&id: &ParamId| store.int(id).unwrap_or(0);
        self.velocity_actuals.iter().all(|id| speed(id) == 0)
    }

    fn motion(&self) -> Motion {
        let state = self.device.state();
        match (state, self.target_velocity) {
            (State::OperationEnabled, Some(target)) => Motion::Following(target),
            (State::FaultReactionActive | State::Fault, _) => Motion::QuickStop,
            (State::QuickStopActive | State::SwitchedOn | State::ReadyToSwitchOn, target) => {
                self.braking_motion(state, target)
            }
            _ => Motion::Disabled,
        }
    }

    /// The motion of a drive braking in `state` after leaving operation enabled: on the slow
    /// down ramp (the setpoint's own deceleration), on the quick stop ramp (6085h), or at once.
    fn braking_motion(&self, state: State, target: Option<ParamId>) -> Motion {
        let at_once = if state == State::QuickStopActive {
            Motion::QuickStop
        } else {
            Motion::Disabled
        };
        match (self.braking, target, self.quick_stop_deceleration) {
            (Some(Braking::SlowDownRamp), Some(target), _) => Motion::RampStop(target),
            (Some(Braking::QuickStopRamp), Some(target), Some(deceleration)) => {
                Motion::RampStopAt(target, deceleration)
            }
            _ => at_once,
        }
    }
}

/// The quirks the description's `[cia402]` table declares (none without one).
pub(crate) fn declared_quirks(store: &Store) -> Quirks {
    let names = store.device().cia402.iter().flat_map(|c| &c.quirks);
    names
        .filter_map(|name| Quirk::from_name(name))
        .fold(Quirks::STANDARD, Quirks::with)
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
        let option = self.quick_stop_option(store);
        self.device.set_quick_stop_option(option);
        let before = self.device.state();
        let taken = self.device.write_controlword(word);
        if taken.is_some_and(|t| t.name == "15") {
            shared.fault = None;
        }
        if before == State::OperationEnabled {
            self.braking = taken.and_then(|t| self.braking_of(store, t.name));
        }
        self.show(store);
        shared.motion = self.motion();
    }

    /// A raised fault takes transition 13, and the automatic transitions follow in the same
    /// tick: the fault reaction and a quick stop are complete at once (the motor stops in one
    /// tick), so fault reaction active is not seen.
    fn tick(&mut self, store: &mut Store, shared: &mut Shared, _dt: Duration) {
        let before = self.device.state();
        if shared.fault.is_some() {
            self.device.raise_fault();
        }
        // A quick stop ending in switch on disabled takes transition 12 once the motor stands
        // (CiA 402: "quick stop completed"); it brakes in quick stop active until then.
        let braking = before == State::QuickStopActive
            && self.device.quick_stop_option() == QuickStopOption::StopThenSwitchOff;
        if !braking || self.stopped(store) {
            self.device.tick();
        }
        if self.device.state() != before {
            self.show(store);
            shared.motion = self.motion();
        }
    }

    /// The mode-specific bits the axis shows (profile position, homing) join the statusword.
    fn settle(&mut self, store: &mut Store, shared: &mut Shared) {
        let word = self.device.statusword() | shared.mode_bits;
        store.set_int(self.statusword, i128::from(word));
    }

    fn reset(&mut self, store: &mut Store, shared: &mut Shared) {
        self.device = Cia402Device::default().with_quirks(self.quirks);
        self.show(store);
        shared.motion = self.motion();
    }
}
