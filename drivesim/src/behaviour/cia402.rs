//! The CiA 402 power state machine on controlword (6040h) and statusword (6041h), with the mode
//! display (6061h) mirroring the requested mode (6060h). Chosen when the description has both
//! 6040h and 6041h. The states, transitions and statuswords are the runtime's device side
//! ([`Cia402Device`]); this behaviour feeds it the controlwords written, the faults raised and
//! the passing of time, and stores its statusword. The velocity setpoint followed in OPERATION
//! ENABLED is 60FFh, or the vl target velocity 6042h on a drive without 60FFh (velocity mode only,
//! e.g. the ez-Wheel SWD).

use std::time::Duration;

use drivebus::control::device::{Cia402Device, QuickStopOption};
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

    fn motion(&self) -> Motion {
        match (self.device.state(), self.target_velocity) {
            (State::OperationEnabled, Some(target)) => Motion::Following(target),
            (State::QuickStopActive | State::FaultReactionActive | State::Fault, _) => {
                Motion::QuickStop
            }
            _ => Motion::Disabled,
        }
    }
}

/// The quirks the description's `[cia402]` table declares (none without one).
fn declared_quirks(store: &Store) -> Quirks {
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
        let taken = self.device.write_controlword(word);
        if taken.is_some_and(|t| t.name == "15") {
            shared.fault = None;
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
        self.device.tick();
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
