//! A positioning axis on the CiA 402 objects: profile position (mode 1) and homing (mode 6),
//! chosen when the description has the controlword, the statusword, a position actual value
//! (6064h, or the internal value 6063h) and the target position (607Ah) or the homing method
//! (6098h). No drive-specific code: every parameter is found by its CiA 402 index, and a missing
//! one is taken as CiA 402's neutral value (no window, no time out, jumps for a zero rate).
//!
//! * Profile position: a rising edge of controlword bit 4 takes 607Ah (relative to the preceding
//!   target with bit 6) and sets the set-point acknowledge (statusword bit 12) until bit 4 falls;
//!   a set-point during a move follows it unless bit 5 (change immediately) is set. The demand
//!   runs the trapezoid of [`trajectory`](super::trajectory) with 6081h, 6083h and 6084h (the
//!   S-curve of [`s_curve`] where the motion profile type 6086h is 1-3); target
//!   reached (bit 10) is the actual position within the position window 6067h of the target
//!   once the demand stands on it, or a standstill under halt (bit 8).
//! * Following error: the actual position follows the demand, unless a test blocks the load
//!   ([`Shared::load_blocked`]); beyond the following error window 6065h for longer than 6066h,
//!   statusword bit 13 is set in profile position mode.
//! * Homing: a rising edge of bit 4 starts the search for the home switch at 6099h sub 1 under
//!   609Ah; on the switch the axis stops and its position becomes minus the home offset 607Ch
//!   (CiA 402: the zero is the home position plus the offset); bit 12 says attained, bit 10 that
//!   homing ended. Methods 35 and 37 home on the position where the axis stands. Without a switch
//!   ([`Shared::home_switch`] `None`) homing fails at once with bit 13. The simulated search goes
//!   straight to the switch, whatever side the method starts on. A drive declaring the
//!   `homing-attained-bit-15` quirk (Kinco) also shows bit 15, `Reference_found`, from a homing
//!   attained until the next start or reboot, in every state; bits 12 and 10 stay as CiA 402
//!   says, which independent masters (python canopen's `homing()`) wait for.
//!   (The manual prints 0xC037, bits 12 and 10 clear, after homing: lines 2498, 3260.)
//! * A quick stop brakes as the quick stop option code 605Ah says, a halt as the halt option
//!   code 605Dh says ([`Braking`]): on the slow down ramp (6084h), the quick stop ramp (6085h),
//!   or at once at the current or voltage limit; without the code a quick stop takes 6085h and a
//!   halt 6084h. Out of operation enabled and quick stop active the load stands where it is.
//! * Cyclic synchronous position (mode 8): each target position (607Ah) written in operation
//!   enabled (an RPDO taken at a SYNC) is reached at an even speed over one interpolation period
//!   (60C2h: sub 1 × 10^sub 2 s; without one, at once); statusword bit 12 says the drive follows
//!   the command value, bit 13 is the following error as in profile position (CiA 402-2, csp).
//! * Cyclic synchronous velocity and torque (modes 9, 10): bit 12 says the drive follows; in
//!   velocity the motor follows the target velocity (60FFh) as in the other velocity modes.
//! * Profile velocity (mode 3): target reached (bit 10) while the motor's speed stands on its
//!   setpoint, speed zero (bit 12) while it is 0. Profile torque (mode 4): target reached while
//!   the torque load's demand stands on the target torque ([`torque`](super::torque)).
//! * In other modes the position integrates the velocity actual value the motor shows (606Ch).

use std::time::Duration;

use drivegen::ir::SpeedPhase;

use drivebus::control::cia402::HALT_BIT;
use drivebus::control::homing::REFERENCE_FOUND;
use drivebus::control::mode_bits::{
    CHANGE_IMMEDIATELY, CYCLIC_SYNC_POSITION, CYCLIC_SYNC_TORQUE, CYCLIC_SYNC_VELOCITY,
    FOLLOWING_ERROR, FOLLOWS_COMMAND, HOMING, HOMING_ATTAINED, HOMING_ERROR, NEW_SET_POINT,
    PROFILE_POSITION, PROFILE_TORQUE, PROFILE_VELOCITY, RELATIVE, SET_POINT_ACKNOWLEDGE,
    SPEED_ZERO, TARGET_REACHED,
};
use drivebus::control::stop_option::Braking;

use super::s_curve::{self, SCurve};
use super::trajectory::{Heading, Kinematics, Profile};
use super::{object, Behaviour, Shared};
use crate::store::{ParamId, Store};

/// The objects the axis reads and shows, looked up once.
#[derive(Debug, Default)]
struct Objects {
    controlword: ParamId,
    statusword: ParamId,
    mode: Option<ParamId>,
    actuals: Vec<ParamId>,
    velocity_actual: Option<ParamId>,
    target: Option<ParamId>,
    profile_velocity: Option<ParamId>,
    acceleration: Option<ParamId>,
    deceleration: Option<ParamId>,
    quick_stop_deceleration: Option<ParamId>,
    quick_stop_option: Option<ParamId>,
    halt_option: Option<ParamId>,
    motion_profile_type: Option<ParamId>,
    following_window: Option<ParamId>,
    following_time_out: Option<ParamId>,
    following_actual: Option<ParamId>,
    position_window: Option<ParamId>,
    homing_method: Option<ParamId>,
    homing_speed: Option<ParamId>,
    homing_acceleration: Option<ParamId>,
    home_offset: Option<ParamId>,
    interpolation_value: Option<ParamId>,
    interpolation_index: Option<ParamId>,
}

/// A cyclic synchronous position set-point being reached: the speed that reaches it in one
/// interpolation period, and the set-point.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Segment {
    velocity: f64,
    end: f64,
}

/// Where a homing run is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
enum Homing {
    #[default]
    Idle,
    Searching,
    Attained,
    Failed,
}

/// The simulated axis.
#[derive(Debug)]
pub struct Axis {
    ids: Objects,
    demand: Kinematics,
    actual: f64,
    /// The set-point in force and whether the demand still travels to it.
    target: f64,
    moving: bool,
    /// A set-point taken during a move, started when the move ends (single set-point).
    pending: Option<f64>,
    acknowledged: bool,
    homing: Homing,
    /// Seconds the following error has been beyond its window.
    beyond_window: f64,
    controlword: u16,
    /// The cyclic synchronous position set-point in progress.
    segment: Option<Segment>,
    /// The drive declares the `homing-attained-bit-15` quirk: it shows statusword bit 15
    /// (Kinco's `Reference_found`) from a homing attained to the next start or reboot.
    shows_reference: bool,
    referenced: bool,
    /// The S-curve of the profile position move in progress (6086h 1-3).
    s_curve: Option<SCurve>,
}

/// The CiA 402 state coding of operation enabled and quick stop active (statusword bits 0-3, 5, 6).
const STATE_MASK: u16 = 0x006F;
const OPERATION_ENABLED: u16 = 0x0027;
const QUICK_STOP_ACTIVE: u16 = 0x0007;
/// Homing methods 35 and 37: the position where the axis stands is home (CiA 402).
const HOME_HERE: [i128; 2] = [35, 37];

impl Axis {
    /// Present when the description has 6040h, 6041h, 6064h or 6063h, and 607Ah or 6098h.
    pub fn detect(store: &mut Store) -> Option<Self> {
        let at = |index| object(store, index, 0);
        let actuals: Vec<ParamId> = [0x6064, 0x6063].into_iter().filter_map(at).collect();
        let ids = Objects {
            controlword: at(0x6040)?,
            statusword: at(0x6041)?,
            mode: at(0x6061),
            velocity_actual: at(0x606C),
            target: at(0x607A),
            profile_velocity: at(0x6081),
            acceleration: at(0x6083),
            deceleration: at(0x6084),
            quick_stop_deceleration: at(0x6085),
            quick_stop_option: at(0x605A),
            halt_option: at(0x605D),
            motion_profile_type: at(0x6086),
            following_window: at(0x6065),
            following_time_out: at(0x6066),
            following_actual: at(0x60F4),
            position_window: at(0x6067),
            homing_method: at(0x6098),
            homing_speed: object(store, 0x6099, 1),
            homing_acceleration: at(0x609A),
            home_offset: at(0x607C),
            interpolation_value: object(store, 0x60C2, 1),
            interpolation_index: object(store, 0x60C2, 2),
            actuals,
        };
        if ids.actuals.is_empty() || (ids.target.is_none() && ids.homing_method.is_none()) {
            return None;
        }
        let shows_reference = super::cia402::declared_quirks(store).homing_attained_bit_15;
        Some(Self::at_power_on(ids, shows_reference))
    }

    /// Standing at 0, nothing commanded, not referenced.
    fn at_power_on(ids: Objects, shows_reference: bool) -> Self {
        Self {
            ids,
            demand: Kinematics::default(),
            actual: 0.0,
            target: 0.0,
            moving: false,
            pending: None,
            acknowledged: false,
            homing: Homing::Idle,
            beyond_window: 0.0,
            controlword: 0,
            segment: None,
            shows_reference,
            referenced: false,
            s_curve: None,
        }
    }

    fn value(store: &Store, id: Option<ParamId>) -> Option<f64> {
        id.and_then(|id| store.int(id)).map(|v| v as f64)
    }

    fn mode(&self, store: &Store) -> i8 {
        Self::value(store, self.ids.mode).map_or(0, |m| m as i8)
    }

    fn state(&self, store: &Store) -> u16 {
        store.int(self.ids.statusword).unwrap_or(0) as u16 & STATE_MASK
    }

    /// The move limits: the homing speed and acceleration in homing mode, the profile's else.
    fn profile(&self, store: &Store, mode: i8) -> Profile {
        let get = |id| Self::value(store, id).unwrap_or(0.0);
        if mode == HOMING {
            let rate = get(self.ids.homing_acceleration);
            return Profile {
                velocity: get(self.ids.homing_speed),
                acceleration: rate,
                deceleration: rate,
            };
        }
        Profile {
            velocity: get(self.ids.profile_velocity),
            acceleration: get(self.ids.acceleration),
            deceleration: get(self.ids.deceleration),
        }
    }

    /// The braking option code held in `id`, decoded by `decode`.
    fn code(
        &self,
        store: &Store,
        id: Option<ParamId>,
        decode: fn(i128) -> Option<Braking>,
    ) -> Option<Braking> {
        id.and_then(|id| store.int(id)).and_then(decode)
    }

    /// The deceleration of `braking`: the profile's (the slow down ramp), the quick stop
    /// deceleration 6085h (the quick stop ramp; the profile's without one), or 0, at once (the
    /// current and voltage limits, the drive disabled).
    fn braking_deceleration(&self, store: &Store, braking: Braking, profile: &Profile) -> f64 {
        match braking {
            Braking::SlowDownRamp => profile.deceleration,
            Braking::QuickStopRamp => {
                Self::value(store, self.ids.quick_stop_deceleration).unwrap_or(profile.deceleration)
            }
            Braking::CurrentLimit | Braking::VoltageLimit | Braking::DisableDriveFunction => 0.0,
        }
    }

    /// A new set-point (rising edge of bit 4 in profile position mode).
    fn take_set_point(&mut self, store: &Store, controlword: u16) {
        let value = Self::value(store, self.ids.target).unwrap_or(0.0);
        let base = self.pending.unwrap_or(self.target);
        let set_point = if controlword & RELATIVE != 0 {
            base + value
        } else {
            value
        };
        if self.moving && controlword & CHANGE_IMMEDIATELY == 0 {
            self.pending = Some(set_point);
        } else {
            self.target = set_point;
            self.moving = true;
        }
        self.acknowledged = true;
    }

    /// The interpolation period (60C2h) in seconds; 0 without one.
    fn interpolation_period(&self, store: &Store) -> f64 {
        let value = Self::value(store, self.ids.interpolation_value).unwrap_or(0.0);
        let index = Self::value(store, self.ids.interpolation_index).unwrap_or(-3.0);
        value * 10f64.powi(index as i32)
    }

    /// A cyclic synchronous position set-point (607Ah written in mode 8): reached at an even
    /// speed over one interpolation period.
    fn take_cyclic_set_point(&mut self, store: &Store) {
        let end = Self::value(store, self.ids.target).unwrap_or(0.0);
        let period = self.interpolation_period(store);
        let velocity = if period > 0.0 {
            (end - self.demand.position) / period
        } else {
            0.0
        };
        self.segment = Some(Segment { velocity, end });
        if period <= 0.0 {
            self.demand.position = end;
        }
    }

    /// Moves the demand along the set-point in progress for `seconds`, standing on its end.
    fn follow_segment(&mut self, seconds: f64) {
        let Some(segment) = self.segment else {
            self.demand.velocity = 0.0;
            return;
        };
        let step = segment.velocity * seconds;
        let to_go = segment.end - self.demand.position;
        if step.abs() >= to_go.abs() || segment.velocity == 0.0 {
            self.demand = Kinematics {
                position: segment.end,
                velocity: 0.0,
            };
            self.segment = None;
        } else {
            self.demand = Kinematics {
                position: self.demand.position + step,
                velocity: segment.velocity,
            };
        }
    }

    /// Starts homing (rising edge of bit 4 in homing mode).
    fn start_homing(&mut self, store: &Store, shared: &mut Shared) {
        let method = Self::value(store, self.ids.homing_method).map_or(0, |m| m as i128);
        self.homing = Homing::Searching;
        self.referenced = false;
        if HOME_HERE.contains(&method) {
            self.home(store, self.demand.position, shared);
        } else if shared.home_switch.0.is_none() {
            self.homing = Homing::Failed;
        }
    }

    /// The axis is on home at `here`: stop, and make `here` minus the home offset.
    fn home(&mut self, store: &Store, here: f64, shared: &mut Shared) {
        let offset = Self::value(store, self.ids.home_offset).unwrap_or(0.0);
        let shift = -offset - here;
        self.demand = Kinematics {
            position: self.demand.position + shift,
            velocity: 0.0,
        };
        self.actual += shift;
        self.target = self.demand.position;
        self.moving = false;
        self.pending = None;
        self.homing = Homing::Attained;
        self.referenced = true;
        self.s_curve = None;
        shared.home_switch.shift(shift);
    }

    /// Moves the demand for `seconds` as the state, the mode and the controlword say.
    fn run(&mut self, store: &Store, shared: &mut Shared, seconds: f64) {
        let mode = self.mode(store);
        let state = self.state(store);
        if mode != PROFILE_POSITION || (state != OPERATION_ENABLED && state != QUICK_STOP_ACTIVE) {
            // The S-curve belongs to the profile position move it started with.
            self.s_curve = None;
        }
        if state != OPERATION_ENABLED && state != QUICK_STOP_ACTIVE {
            self.demand = Kinematics {
                position: self.actual,
                velocity: 0.0,
            };
            self.target = self.actual;
            self.moving = false;
            self.pending = None;
            self.segment = None;
            if self.homing == Homing::Searching {
                self.homing = Homing::Idle;
            }
            return;
        }
        let mut profile = self.profile(store, mode);
        let heading = if state == QUICK_STOP_ACTIVE {
            // Without 605Ah (or a code of its own) the quick stop ramp, as before codes were read.
            let braking = self.code(store, self.ids.quick_stop_option, Braking::quick_stop);
            profile.deceleration = self.braking_deceleration(
                store,
                braking.unwrap_or(Braking::QuickStopRamp),
                &profile,
            );
            Heading::Stop
        } else if self.controlword & HALT_BIT != 0 {
            let braking = self.code(store, self.ids.halt_option, Braking::halt);
            profile.deceleration = self.braking_deceleration(
                store,
                braking.unwrap_or(Braking::SlowDownRamp),
                &profile,
            );
            Heading::Stop
        } else if mode == CYCLIC_SYNC_POSITION {
            self.follow_segment(seconds);
            return;
        } else if mode == PROFILE_POSITION && self.moving {
            Heading::To(self.target)
        } else if mode == HOMING && self.homing == Homing::Searching {
            let switch = shared.home_switch.0.unwrap_or(self.demand.position);
            Heading::At((switch - self.demand.position).signum() * profile.velocity)
        } else if mode == PROFILE_POSITION || mode == HOMING {
            Heading::Stop
        } else {
            // Another mode: the motor's speed moves the load.
            let speed = Self::value(store, self.ids.velocity_actual).unwrap_or(0.0);
            self.demand.velocity = speed;
            self.demand.position += speed * seconds;
            return;
        };
        let switch = shared.home_switch.0;
        match switch.filter(|_| mode == HOMING && self.homing == Homing::Searching) {
            Some(switch) => {
                if self
                    .demand
                    .advance_to_mark(heading, &profile, seconds, switch)
                {
                    self.home(store, switch, shared);
                }
            }
            None => self.advance_demand(store, mode, heading, &profile, seconds),
        }
        if self.moving && self.demand.arrived(self.target) {
            self.moving = false;
            if let Some(next) = self.pending.take() {
                self.target = next;
                self.moving = true;
            }
        }
    }

    /// Moves the demand for `seconds` towards `heading`: on the trapezoid, or in profile
    /// position mode on the S-curve the motion profile type (6086h) selects.
    fn advance_demand(
        &mut self,
        store: &Store,
        mode: i8,
        heading: Heading,
        profile: &Profile,
        seconds: f64,
    ) {
        let kind = Self::value(store, self.ids.motion_profile_type).map_or(0, |k| k as i128);
        let window = s_curve::window(kind, profile).filter(|_| mode == PROFILE_POSITION);
        match window {
            Some(window) => {
                let start = self.demand;
                self.s_curve
                    .get_or_insert_with(|| SCurve::from(start, window))
                    .advance(&mut self.demand, heading, profile, seconds);
            }
            None => {
                self.s_curve = None;
                self.demand.advance(heading, profile, seconds);
            }
        }
    }

    /// The following error supervision: how long the error has been beyond its window.
    fn supervise(&mut self, store: &Store, seconds: f64) -> bool {
        let window = Self::value(store, self.ids.following_window).unwrap_or(f64::INFINITY);
        // CiA 402: a window of FFFFFFFFh switches the supervision off.
        if window >= f64::from(u32::MAX) || (self.demand.position - self.actual).abs() <= window {
            self.beyond_window = 0.0;
            return false;
        }
        self.beyond_window += seconds;
        let time_out = Self::value(store, self.ids.following_time_out).unwrap_or(0.0) / 1000.0;
        self.beyond_window > time_out
    }

    /// The mode-specific statusword bits 10, 12 and 13.
    fn mode_bits(&self, store: &Store, shared: &Shared, following_error: bool) -> u16 {
        if self.state(store) != OPERATION_ENABLED {
            return 0;
        }
        let halted = self.controlword & HALT_BIT != 0 && self.demand.velocity == 0.0;
        match self.mode(store) {
            PROFILE_POSITION => {
                let window = Self::value(store, self.ids.position_window).unwrap_or(0.0);
                let on_target = !self.moving && (self.target - self.actual).abs() <= window;
                bit(on_target || halted, TARGET_REACHED)
                    | bit(self.acknowledged, SET_POINT_ACKNOWLEDGE)
                    | bit(following_error, FOLLOWING_ERROR)
            }
            HOMING => {
                let ended = matches!(self.homing, Homing::Attained | Homing::Failed);
                bit(ended || halted, TARGET_REACHED)
                    | bit(self.homing == Homing::Attained, HOMING_ATTAINED)
                    | bit(self.homing == Homing::Failed, HOMING_ERROR)
            }
            CYCLIC_SYNC_POSITION => {
                bit(true, FOLLOWS_COMMAND) | bit(following_error, FOLLOWING_ERROR)
            }
            CYCLIC_SYNC_VELOCITY | CYCLIC_SYNC_TORQUE => FOLLOWS_COMMAND,
            PROFILE_VELOCITY => {
                let speed = Self::value(store, self.ids.velocity_actual).unwrap_or(0.0);
                let at_target = matches!(shared.phase, Some(SpeedPhase::Steady | SpeedPhase::Zero));
                bit(at_target || halted, TARGET_REACHED) | bit(speed == 0.0, SPEED_ZERO)
            }
            PROFILE_TORQUE => bit(shared.torque_reached || halted, TARGET_REACHED),
            _ => 0,
        }
    }

    /// Shows the positions, the speed (in the positioning modes) and the mode bits.
    fn show(&self, store: &mut Store, shared: &mut Shared, following_error: bool) {
        for &id in &self.ids.actuals {
            store.set_int(id, self.actual.round() as i128);
        }
        if let Some(id) = self.ids.following_actual {
            store.set_int(id, (self.demand.position - self.actual).round() as i128);
        }
        let mode = self.mode(store);
        if let (Some(id), true) = (
            self.ids.velocity_actual,
            matches!(mode, PROFILE_POSITION | HOMING | CYCLIC_SYNC_POSITION),
        ) {
            store.set_int(id, self.demand.velocity.round() as i128);
        }
        let reference = bit(self.shows_reference && self.referenced, REFERENCE_FOUND);
        shared.mode_bits = self.mode_bits(store, shared, following_error) | reference;
    }

    fn advance(&mut self, store: &mut Store, shared: &mut Shared, seconds: f64) {
        self.run(store, shared, seconds);
        if !shared.load_blocked {
            self.actual = self.demand.position;
        }
        let following_error = self.supervise(store, seconds);
        self.show(store, shared, following_error);
    }
}

const fn bit(set: bool, mask: u16) -> u16 {
    if set {
        mask
    } else {
        0
    }
}

impl Behaviour for Axis {
    fn written(&mut self, store: &mut Store, shared: &mut Shared, id: ParamId) {
        if id == self.ids.controlword {
            let word = store.int(id).unwrap_or(0) as u16;
            let rising = word & NEW_SET_POINT != 0 && self.controlword & NEW_SET_POINT == 0;
            let enabled = self.state(store) == OPERATION_ENABLED;
            match self.mode(store) {
                PROFILE_POSITION if rising && enabled => self.take_set_point(store, word),
                HOMING if rising && enabled => self.start_homing(store, shared),
                HOMING if word & NEW_SET_POINT == 0 && self.homing == Homing::Searching => {
                    self.homing = Homing::Idle;
                }
                _ => {}
            }
            if word & NEW_SET_POINT == 0 {
                self.acknowledged = false;
            }
            self.controlword = word;
        }
        let enabled = self.state(store) == OPERATION_ENABLED;
        if Some(id) == self.ids.target && enabled && self.mode(store) == CYCLIC_SYNC_POSITION {
            self.take_cyclic_set_point(store);
        }
        self.advance(store, shared, 0.0);
    }

    fn tick(&mut self, store: &mut Store, shared: &mut Shared, dt: Duration) {
        self.advance(store, shared, dt.as_secs_f64());
    }

    /// A reboot loses the position (an incremental encoder) and any move.
    fn reset(&mut self, store: &mut Store, shared: &mut Shared) {
        *self = Self::at_power_on(std::mem::take(&mut self.ids), self.shows_reference);
        self.advance(store, shared, 0.0);
    }
}
