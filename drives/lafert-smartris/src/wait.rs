//! Waiting for the drive without assuming an operating system: a [`Clock`] tells the time and
//! sleeps; [`StdClock`] (feature `std`) is the ordinary one, tests and firmware bring their own.

use core::time::Duration;

/// Monotonic time and sleeping, as the helpers that wait for the drive need them.
pub trait Clock {
    /// Time since an arbitrary, fixed origin; never goes backwards.
    fn now(&mut self) -> Duration;
    /// Blocks for `duration`.
    fn sleep(&mut self, duration: Duration);
}

/// `std::time::Instant` and `std::thread::sleep`.
#[cfg(feature = "std")]
#[derive(Debug, Clone, Copy)]
pub struct StdClock {
    origin: std::time::Instant,
}

#[cfg(feature = "std")]
impl StdClock {
    /// A clock whose origin is now.
    pub fn new() -> Self {
        Self {
            origin: std::time::Instant::now(),
        }
    }
}

#[cfg(feature = "std")]
impl Default for StdClock {
    fn default() -> Self {
        Self::new()
    }
}

#[cfg(feature = "std")]
impl Clock for StdClock {
    fn now(&mut self) -> Duration {
        self.origin.elapsed()
    }

    fn sleep(&mut self, duration: Duration) {
        std::thread::sleep(duration);
    }
}

/// How long to wait for the drive to answer again after a system reset, and how often to ask.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RebootWait {
    /// Give up when the drive has not answered this long after the reset command.
    pub deadline: Duration,
    /// Pause between two attempts to reach the drive.
    pub poll_interval: Duration,
}

impl Default for RebootWait {
    /// The Modbus manual (§4.2 SYSTEM RESET, line 1464) says to wait "about 2 sec"; the default
    /// allows twice that and asks every 250 ms.
    fn default() -> Self {
        Self {
            deadline: Duration::from_secs(4),
            poll_interval: Duration::from_millis(250),
        }
    }
}
