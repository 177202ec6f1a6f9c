//! The Lafert Smartris state machine in Modbus command mode (RTU Modbus manual rel. 1.4b §4.2.1
//! "Run Sequence", Table 3): STANDBY after power-on (T0, T1); control word 0x0003 → RUN (T2 from
//! standby, T5 from stop); 0x0001 → STOP with maximum torque (T4); run bit clear → STANDBY (T3,
//! T6); a fault → ALARM (T7, T8), left only by a system reset (T9). The drive status input
//! register shows the state; the operation mode register (after store + reset) picks velocity or
//! torque RUN.
//!
//! The behaviour is chosen when the description has a `control_word` with `run` and
//! `stop_disabled` bits and a `drive_status` with `standby`, `stop` and `run_velocity` bits.

use std::time::Duration;

use super::{flag_bit, Behaviour, Motion, Shared};
use crate::refusal::Refusal;
use crate::store::{ParamId, Store};

/// Raw operation mode value selecting torque mode (manual §4.2, line 1441).
const TORQUE_MODE: i128 = 1;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum State {
    Standby,
    Run,
    Stop,
    Fault,
}

/// Bit masks of the registers involved, read from the description's flag types.
#[derive(Debug, Clone, Copy)]
struct Bits {
    run: u32,
    stop_disabled: u32,
    standby: u32,
    stop: u32,
    run_velocity: u32,
    run_torque: Option<u32>,
    alarm: Option<u32>,
}

/// The Lafert Modbus-mode state machine.
#[derive(Debug)]
pub struct LafertModbus {
    control_word: ParamId,
    drive_status: ParamId,
    speed_setpoint: Option<ParamId>,
    full_scale_velocity: Option<ParamId>,
    operation_mode: Option<ParamId>,
    error_code: Option<ParamId>,
    bits: Bits,
    state: State,
    torque_mode: bool,
}

impl LafertModbus {
    /// Present when the description has the Lafert control word and drive status; starts in
    /// STANDBY.
    pub fn detect(store: &mut Store) -> Option<Self> {
        let control_word = store.id("control_word")?;
        let drive_status = store.id("drive_status")?;
        let bits = Bits {
            run: flag_bit(store, control_word, "run")?,
            stop_disabled: flag_bit(store, control_word, "stop_disabled")?,
            standby: flag_bit(store, drive_status, "standby")?,
            stop: flag_bit(store, drive_status, "stop")?,
            run_velocity: flag_bit(store, drive_status, "run_velocity")?,
            run_torque: flag_bit(store, drive_status, "run_torque"),
            alarm: flag_bit(store, drive_status, "alarm"),
        };
        let mut machine = Self {
            control_word,
            drive_status,
            speed_setpoint: store.id("speed_setpoint"),
            full_scale_velocity: store.id("full_scale_velocity"),
            operation_mode: store.id("operation_mode"),
            error_code: store.id("error_code"),
            bits,
            state: State::Standby,
            torque_mode: false,
        };
        machine.power_on(store);
        Some(machine)
    }

    /// T0/T1: init without alarm ends in STANDBY; the operation mode read at boot is the one used.
    fn power_on(&mut self, store: &mut Store) {
        self.torque_mode = self
            .operation_mode
            .and_then(|id| store.int(id))
            .is_some_and(|mode| mode == TORQUE_MODE);
        self.enter(store, State::Standby);
    }

    fn enter(&mut self, store: &mut Store, state: State) {
        self.state = state;
        let bit = match state {
            State::Standby => Some(self.bits.standby),
            State::Stop => Some(self.bits.stop),
            State::Run if self.torque_mode => self.bits.run_torque,
            State::Run => Some(self.bits.run_velocity),
            State::Fault => self.bits.alarm,
        };
        store.set_int(self.drive_status, bit.map_or(0, |b| 1 << b));
    }

    fn motion(&self) -> Motion {
        match (self.state, self.speed_setpoint) {
            (State::Run, Some(setpoint)) if !self.torque_mode => Motion::Following(setpoint),
            (State::Stop | State::Fault, _) => Motion::QuickStop,
            _ => Motion::Disabled,
        }
    }

    /// The state a control word written in `self.state` leads to.
    fn next(&self, word: i128) -> State {
        let run = word & (1 << self.bits.run) != 0;
        let stop_disabled = word & (1 << self.bits.stop_disabled) != 0;
        match (self.state, run, stop_disabled) {
            (State::Fault, _, _) => State::Fault,
            (_, false, _) => State::Standby, // T3, T6
            (_, true, true) => State::Run,   // T2, T5
            (State::Run | State::Stop, true, false) => State::Stop, // T4
            (State::Standby, true, false) => State::Standby,
        }
    }
}

impl Behaviour for LafertModbus {
    /// The speed setpoint is bounded by ± the full-scale velocity (holding 0x0003; manual §4.2,
    /// line 1333) once the drive knows it (non-zero).
    fn accept(&self, store: &Store, id: ParamId, bytes: &[u8]) -> Result<(), Refusal> {
        if Some(id) != self.speed_setpoint {
            return Ok(());
        }
        let full_scale = self
            .full_scale_velocity
            .and_then(|f| store.int(f))
            .unwrap_or(0);
        let value = crate::raw::to_int(store.parameter(id).data_type, bytes).unwrap_or(0);
        match value {
            _ if full_scale == 0 => Ok(()),
            v if v > full_scale => Err(Refusal::TooHigh),
            v if v < -full_scale => Err(Refusal::TooLow),
            _ => Ok(()),
        }
    }

    fn written(&mut self, store: &mut Store, shared: &mut Shared, id: ParamId) {
        if id != self.control_word {
            return;
        }
        let word = store.int(id).unwrap_or(0);
        let next = self.next(word);
        self.enter(store, next);
        shared.motion = self.motion();
    }

    /// T7/T8: an injected fault stops the drive and shows the alarm and its code.
    fn tick(&mut self, store: &mut Store, shared: &mut Shared, _dt: Duration) {
        if let (Some(code), true) = (shared.fault, self.state != State::Fault) {
            self.enter(store, State::Fault);
            if let Some(id) = self.error_code {
                store.set_int(id, i128::from(code));
            }
            shared.motion = self.motion();
        }
    }

    /// T9: the reset command clears the fault; the drive boots into STANDBY.
    fn reset(&mut self, store: &mut Store, shared: &mut Shared) {
        shared.fault = None;
        self.power_on(store);
        shared.motion = self.motion();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn machine(state: State) -> LafertModbus {
        LafertModbus {
            control_word: 0,
            drive_status: 1,
            speed_setpoint: None,
            full_scale_velocity: None,
            operation_mode: None,
            error_code: None,
            bits: Bits {
                run: 0,
                stop_disabled: 1,
                standby: 1,
                stop: 2,
                run_velocity: 0,
                run_torque: Some(5),
                alarm: Some(4),
            },
            state,
            torque_mode: false,
        }
    }

    #[test]
    fn table_3_transitions_follow_the_control_word() {
        assert_eq!(machine(State::Standby).next(0x0003), State::Run); // T2
        assert_eq!(machine(State::Run).next(0x0001), State::Stop); // T4
        assert_eq!(machine(State::Stop).next(0x0003), State::Run); // T5
        assert_eq!(machine(State::Stop).next(0x0002), State::Standby); // T6
        assert_eq!(machine(State::Run).next(0x0002), State::Standby); // T3
        assert_eq!(machine(State::Standby).next(0x0001), State::Standby);
        assert_eq!(machine(State::Fault).next(0x0003), State::Fault);
    }
}
