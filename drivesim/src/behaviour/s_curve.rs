//! An S-curve move made from the trapezoid (CiA 402 motion profile types 1-3, 6086h): the
//! trapezoid of [`trajectory`](super::trajectory) runs as the reference, and the demand moves at
//! the reference's speed averaged over a window of `T` seconds. Averaging a trapezoid's speed
//! over `T` turns each step of its acceleration into a ramp of length `T`: the acceleration
//! changes at most at `a / T` (the jerk), the speed bends into and out of each ramp, and, the
//! average keeping the integral, the demand stops exactly where the reference stopped, `T`
//! later. Pure: the axis feeds it time.

use std::collections::VecDeque;

use super::trajectory::{Heading, Kinematics, Profile, STEP};

/// The reference trapezoid and the window of its last speeds.
#[derive(Debug, Clone)]
pub struct SCurve {
    reference: Kinematics,
    window: VecDeque<f64>,
    sum: f64,
}

impl SCurve {
    /// An S-curve from `start` (position and speed, standing or moving), averaging over
    /// `window` seconds (at least one step).
    pub fn from(start: Kinematics, window: f64) -> Self {
        let steps = ((window / STEP).round() as usize).max(1);
        Self {
            reference: start,
            window: std::iter::repeat_n(start.velocity, steps).collect(),
            sum: start.velocity * steps as f64,
        }
    }

    /// Advances `demand` by `seconds` towards `heading` within `profile`, in steps of
    /// [`STEP`]: the reference takes the trapezoid's step, the demand the window's average.
    /// Once the reference stands and the window holds only its standstill, the demand stands on
    /// the reference's position.
    pub fn advance(
        &mut self,
        demand: &mut Kinematics,
        heading: Heading,
        profile: &Profile,
        seconds: f64,
    ) {
        let mut left = seconds;
        while left > 0.0 {
            let h = left.min(STEP);
            self.reference.step(heading, profile, h);
            self.window.push_back(self.reference.velocity);
            let oldest = self.window.pop_front().unwrap_or(0.0);
            self.sum += self.reference.velocity - oldest;
            demand.velocity = self.sum / self.window.len() as f64;
            demand.position += demand.velocity * h;
            left -= h;
        }
        if self.window.iter().all(|&v| v == 0.0) {
            // The average's rounding aside, the demand is where the reference stopped.
            self.sum = 0.0;
            *demand = Kinematics {
                position: self.reference.position,
                velocity: 0.0,
            };
        }
    }
}

/// The averaging window of motion profile type `kind` (6086h), in seconds: for CiA 402's sin²
/// (1), jerk-free (2) and jerk-limited (3) ramps, half the time the linear ramp takes to reach
/// the profile velocity, `v / (2·a)` (a jerk of `2·a²/v`, no part at constant acceleration, as a
/// sin² ramp has); `None`, a trapezoid, for the linear ramp (0), the manufacturers' values and a
/// zero rate. The three are not told apart: the profile has no jerk object (60A4h).
pub fn window(kind: i128, profile: &Profile) -> Option<f64> {
    let standard = (1..=3).contains(&kind);
    let rates = profile.velocity > 0.0 && profile.acceleration > 0.0;
    (standard && rates).then(|| profile.velocity / (2.0 * profile.acceleration))
}

#[cfg(test)]
mod tests {
    use super::*;

    const PROFILE: Profile = Profile {
        velocity: 10_000.0,
        acceleration: 20_000.0,
        deceleration: 20_000.0,
    };

    /// The largest jerk of a move, on its ramps and over the whole of it.
    struct Jerk {
        ramps: f64,
        whole: f64,
    }

    /// A move to 20 000 sampled every step: the largest change of the acceleration per second
    /// (the jerk) while the trapezoid moves (its ramps) and over the whole move, and the
    /// seconds it took; `s_curve` or the trapezoid.
    fn profile_of(s_curve: bool) -> (Jerk, f64) {
        let mut demand = Kinematics::default();
        let mut curve = SCurve::from(demand, window(1, &PROFILE).unwrap());
        let (mut velocity, mut acceleration, mut seconds) = (0.0, 0.0, 0.0);
        let mut jerk = Jerk {
            ramps: 0.0,
            whole: 0.0,
        };
        while !demand.arrived(20_000.0) {
            assert!(seconds < 10.0, "{demand:?}");
            if s_curve {
                curve.advance(&mut demand, Heading::To(20_000.0), &PROFILE, STEP);
            } else {
                demand.advance(Heading::To(20_000.0), &PROFILE, STEP);
            }
            let now = (demand.velocity - velocity) / STEP;
            let this = (now - acceleration).abs() / STEP;
            jerk.whole = jerk.whole.max(this);
            if curve.reference.velocity > 0.0 || !s_curve {
                jerk.ramps = jerk.ramps.max(this);
            }
            (velocity, acceleration) = (demand.velocity, now);
            seconds += STEP;
        }
        (jerk, seconds)
    }

    #[test]
    fn the_s_curve_bends_the_ramps_the_trapezoid_breaks_and_stops_on_the_same_target() {
        let (trapezoid, trapezoid_time) = profile_of(false);
        let (s, s_time) = profile_of(true);
        // The trapezoid's acceleration jumps by 20 000/s² within a step or two.
        assert!(trapezoid.ramps >= 5.0e6, "{}", trapezoid.ramps);
        // The S-curve's changes by 2·a²/v = 80 000/s³ on the ramps, while the trapezoid moves
        // forward. The trapezoid settles on the target by passing it by a few units and coming
        // back, then stands on it from a crawl (a speed step of up to 4·dec·h + 1): through the
        // window those give a few short jerks of their own, still a small part of the
        // trapezoid's.
        assert!(s.ramps <= 8.1e4, "{}", s.ramps);
        assert!(
            s.whole * 20.0 <= trapezoid.whole,
            "{} / {}",
            s.whole,
            trapezoid.whole
        );
        // It arrives one window (0.25 s) later, exactly on the target (the loop's condition).
        let later = s_time - trapezoid_time;
        assert!((0.2..=0.3).contains(&later), "{later}");
    }

    #[test]
    fn only_the_standard_s_curve_types_have_a_window() {
        assert_eq!(window(0, &PROFILE), None);
        assert_eq!(window(-2, &PROFILE), None, "manufacturer specific");
        assert_eq!(window(3, &PROFILE), Some(0.25));
        let instant = Profile {
            acceleration: 0.0,
            ..PROFILE
        };
        assert_eq!(window(1, &instant), None);
    }
}
