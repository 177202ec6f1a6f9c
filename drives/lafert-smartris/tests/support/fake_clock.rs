//! A clock that only moves when slept on: deterministic waits without real sleeping.

use core::time::Duration;

use lafert_smartris::Clock;

#[derive(Debug, Default)]
pub struct FakeClock {
    pub now: Duration,
    pub sleeps: u32,
}

impl Clock for FakeClock {
    fn now(&mut self) -> Duration {
        self.now
    }
    fn sleep(&mut self, duration: Duration) {
        self.now += duration;
        self.sleeps += 1;
    }
}
