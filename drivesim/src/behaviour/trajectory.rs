//! A trapezoidal move on one axis: the speed rises at the acceleration up to the profile velocity
//! and falls at the deceleration so as to stop on the target (CiA 402 motion profile type 0,
//! linear ramp). Pure: the axis behaviour feeds it time in small steps.
//!
//! Units are the description's raw ones: positions in position units, speeds in velocity units
//! taken as position units per second and accelerations as velocity units per second — CiA 402's
//! default factor group (increments, increments per second). A drive whose velocity unit is
//! something else (Kinco's DEC) moves at another pace than the real one, consistently.

/// Position and speed of the simulated load.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Kinematics {
    /// Position, in position units.
    pub position: f64,
    /// Speed, in position units per second.
    pub velocity: f64,
}

/// The limits of a move, in position units per second and per second squared; a rate of 0 is
/// taken as "at once".
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Profile {
    /// Largest speed (6081h, or a homing speed).
    pub velocity: f64,
    /// Speed change away from zero (6083h, or 609Ah).
    pub acceleration: f64,
    /// Speed change towards zero (6084h, 6085h on a quick stop, or 609Ah).
    pub deceleration: f64,
}

/// Length of one integration step: fine enough that a move stops on its target within a
/// rounding, coarse enough that a second of simulated time is a thousand steps.
pub const STEP: f64 = 0.001;

/// Where the axis heads.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Heading {
    /// To this position, stopping on it.
    To(f64),
    /// At this signed speed, without end (a homing search).
    At(f64),
    /// To a standstill wherever the deceleration ends (halt, quick stop).
    Stop,
}

impl Kinematics {
    /// Whether the axis stands on `target`.
    pub fn arrived(&self, target: f64) -> bool {
        self.velocity == 0.0 && self.position == target
    }

    /// Advances by `seconds` towards `heading` within `profile`, in steps of [`STEP`].
    pub fn advance(&mut self, heading: Heading, profile: &Profile, seconds: f64) {
        let mut left = seconds;
        while left > 0.0 {
            let h = left.min(STEP);
            self.step(heading, profile, h);
            left -= h;
        }
    }

    /// Advances by up to `seconds` towards `heading`, stopping on `mark` the step it is passed
    /// (a switch that stops the search); says whether it was.
    pub fn advance_to_mark(
        &mut self,
        heading: Heading,
        profile: &Profile,
        seconds: f64,
        mark: f64,
    ) -> bool {
        let mut left = seconds;
        while left > 0.0 {
            let before = self.position;
            let h = left.min(STEP);
            self.step(heading, profile, h);
            if (before - mark) * (self.position - mark) <= 0.0 {
                self.position = mark;
                self.velocity = 0.0;
                return true;
            }
            left -= h;
        }
        false
    }

    /// One step: the speed moves towards the speed wanted here (the profile velocity, less near
    /// the target so the deceleration stops on it), then the position by the speed.
    pub(crate) fn step(&mut self, heading: Heading, profile: &Profile, h: f64) {
        let wanted = match heading {
            Heading::To(target) => {
                let to_go = target - self.position;
                // Close enough that one step at the speed left would pass it, and as slow as the
                // braking curve is one step before the target, 2·dec·h (a zero deceleration
                // stops at once): stand on it.
                let can_stop = profile.deceleration == 0.0
                    || self.velocity.abs() <= 4.0 * profile.deceleration * h + 1.0;
                if to_go.abs() <= (self.velocity.abs() * h).max(0.5) && can_stop {
                    self.position = target;
                    self.velocity = 0.0;
                    return;
                }
                let braking = if profile.deceleration > 0.0 {
                    (2.0 * profile.deceleration * to_go.abs()).sqrt()
                } else {
                    f64::INFINITY
                };
                to_go.signum() * profile.velocity.min(braking)
            }
            Heading::At(speed) => speed,
            Heading::Stop => 0.0,
        };
        let speeding_up = wanted.abs() > self.velocity.abs() && wanted * self.velocity >= 0.0;
        let rate = if speeding_up {
            profile.acceleration
        } else {
            profile.deceleration
        };
        self.velocity = if rate > 0.0 {
            let change = rate * h;
            self.velocity + (wanted - self.velocity).clamp(-change, change)
        } else {
            wanted
        };
        self.position += self.velocity * h;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const PROFILE: Profile = Profile {
        velocity: 10_000.0,
        acceleration: 20_000.0,
        deceleration: 40_000.0,
    };

    #[test]
    fn a_move_rises_cruises_falls_and_stops_on_its_target() {
        let mut axis = Kinematics::default();
        axis.advance(Heading::To(50_000.0), &PROFILE, 0.25);
        // Still accelerating: 20 000/s² for 0.25 s.
        assert!((axis.velocity - 5_000.0).abs() < 1.0, "{axis:?}");
        axis.advance(Heading::To(50_000.0), &PROFILE, 1.0);
        assert_eq!(axis.velocity, 10_000.0, "cruising at the profile velocity");
        // 0.5 s to reach speed (2 500), 0.25 s to stop (1 250), 4.625 s at speed: 5.375 s.
        axis.advance(Heading::To(50_000.0), &PROFILE, 4.1);
        assert!(
            !axis.arrived(50_000.0),
            "not there before its time: {axis:?}"
        );
        axis.advance(Heading::To(50_000.0), &PROFILE, 0.05);
        assert!(axis.arrived(50_000.0), "{axis:?}");
    }

    #[test]
    fn a_stop_decelerates_and_a_search_holds_its_speed() {
        let mut axis = Kinematics::default();
        axis.advance(Heading::At(-8_000.0), &PROFILE, 1.0);
        assert_eq!(axis.velocity, -8_000.0);
        axis.advance(Heading::Stop, &PROFILE, 0.1);
        assert!((axis.velocity + 4_000.0).abs() < 1.0, "{axis:?}");
        axis.advance(Heading::Stop, &PROFILE, 0.2);
        assert_eq!(axis.velocity, 0.0);
    }

    #[test]
    fn a_search_stops_on_its_mark() {
        let mut axis = Kinematics::default();
        assert!(!axis.advance_to_mark(Heading::At(-1_000.0), &PROFILE, 0.5, -600.0));
        assert!(axis.advance_to_mark(Heading::At(-1_000.0), &PROFILE, 0.5, -600.0));
        assert_eq!(
            axis,
            Kinematics {
                position: -600.0,
                velocity: 0.0
            }
        );
    }

    #[test]
    fn zero_rates_jump() {
        let mut axis = Kinematics::default();
        let instant = Profile {
            velocity: 1_000.0,
            ..Profile::default()
        };
        axis.advance(Heading::To(100.0), &instant, 0.2);
        assert!(axis.arrived(100.0), "{axis:?}");
    }
}
