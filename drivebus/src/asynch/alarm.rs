//! [`Alarm`], one deadline a client keeps from request to request, and [`within_alarm`], a
//! timeout over any future measured on it.

use core::future::{poll_fn, Future};
use core::pin::pin;
use core::task::{Context, Poll};
use core::time::Duration;

use super::timer::Elapsed;

/// One deadline that is kept and moved instead of a timer armed afresh for every request: a
/// client takes one from [`Timer::alarm`](super::Timer::alarm) and sets it at each request.
///
/// Why: a sleep per request costs a timer registration and its removal (tokio: both under the
/// timer's lock); moving a kept deadline later costs an atomic store in tokio, the timer
/// seeing the move only when the old deadline comes. An embassy alarm keeps an `Instant` and
/// asks the time driver to wake it then.
pub trait Alarm {
    /// Sets the deadline to `after` from now, replacing the one set before.
    fn set(&mut self, after: Duration);

    /// Ready once the deadline set last has passed; until then pending, `cx`'s waker to be
    /// woken when it passes. Before the first [`set`](Alarm::set) it is never due.
    fn poll_due(&mut self, cx: &mut Context<'_>) -> Poll<()>;
}

impl<A: Alarm + ?Sized> Alarm for &mut A {
    fn set(&mut self, after: Duration) {
        (**self).set(after);
    }

    fn poll_due(&mut self, cx: &mut Context<'_>) -> Poll<()> {
        (**self).poll_due(cx)
    }
}

/// A kept alarm aimed at a transfer's deadline: set only when the deadline moves (a transfer's
/// deadline often stays while its frames come), raced against the transfer's other waits
/// without being given up.
#[cfg_attr(not(feature = "canopen"), allow(dead_code))]
pub(crate) struct Aimed<'a, A: ?Sized> {
    alarm: &'a mut A,
    /// The deadline the alarm is set for, on the transfer's clock.
    at: Option<Duration>,
}

#[cfg_attr(not(feature = "canopen"), allow(dead_code))]
impl<'a, A: Alarm + ?Sized> Aimed<'a, A> {
    /// `alarm`, not aimed yet.
    pub(crate) fn new(alarm: &'a mut A) -> Self {
        Self { alarm, at: None }
    }

    /// Aims the alarm at `deadline`, `now` being the time on the same clock; nothing to do
    /// when it is aimed there already.
    pub(crate) fn aim(&mut self, deadline: Duration, now: Duration) {
        if self.at != Some(deadline) {
            self.alarm.set(deadline.saturating_sub(now));
            self.at = Some(deadline);
        }
    }

    /// Completes once the deadline aimed at has passed; the next [`aim`](Self::aim) sets the
    /// alarm again, even for the same deadline.
    pub(crate) async fn due(&mut self) {
        poll_fn(|cx| self.alarm.poll_due(cx)).await;
        self.at = None;
    }
}

/// Runs `work` for at most `limit`, timed by `alarm` (set here): [`within`](super::within) on
/// a kept alarm. Whichever completes first wins, the work when both are ready; on [`Elapsed`]
/// the work's future has been dropped, so its cancellation handling has run. The alarm stays
/// set when this returns (or is dropped): the next request moves it.
pub async fn within_alarm<T>(
    alarm: &mut impl Alarm,
    limit: Duration,
    work: impl Future<Output = T>,
) -> Result<T, Elapsed> {
    alarm.set(limit);
    let mut work = pin!(work);
    poll_fn(|cx| {
        if let Poll::Ready(value) = work.as_mut().poll(cx) {
            return Poll::Ready(Ok(value));
        }
        alarm.poll_due(cx).map(|()| Err(Elapsed))
    })
    .await
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::task::Waker;

    /// An alarm that is due at once after any `set`, or never; it counts its settings.
    struct Fixed {
        due: bool,
        sets: u32,
    }

    impl Alarm for Fixed {
        fn set(&mut self, _: Duration) {
            self.sets += 1;
        }

        fn poll_due(&mut self, _: &mut Context<'_>) -> Poll<()> {
            match self.due && self.sets > 0 {
                true => Poll::Ready(()),
                false => Poll::Pending,
            }
        }
    }

    fn poll_once<F: Future>(future: F) -> Poll<F::Output> {
        let mut cx = Context::from_waker(Waker::noop());
        pin!(future).poll(&mut cx)
    }

    #[test]
    fn ready_work_wins_even_when_the_alarm_is_due() {
        let mut alarm = Fixed { due: true, sets: 0 };
        let outcome = poll_once(within_alarm(&mut alarm, Duration::ZERO, async { 7 }));
        assert_eq!(outcome, Poll::Ready(Ok(7)));
    }

    #[test]
    fn pending_work_ends_in_elapsed_when_the_alarm_is_due() {
        let mut alarm = Fixed { due: true, sets: 0 };
        let work = core::future::pending::<u8>();
        let outcome = poll_once(within_alarm(&mut alarm, Duration::ZERO, work));
        assert_eq!(outcome, Poll::Ready(Err(Elapsed)));
    }

    #[test]
    fn pending_work_waits_while_the_alarm_is_not_due() {
        let mut alarm = Fixed {
            due: false,
            sets: 0,
        };
        let work = core::future::pending::<u8>();
        let outcome = poll_once(within_alarm(&mut alarm, Duration::ZERO, work));
        assert_eq!(outcome, Poll::Pending);
    }

    #[test]
    fn every_wait_sets_the_alarm_once() {
        let mut alarm = Fixed {
            due: false,
            sets: 0,
        };
        for _ in 0..3 {
            let _ = poll_once(within_alarm(&mut alarm, Duration::ZERO, async { 1 }));
        }
        assert_eq!(alarm.sets, 3);
    }

    /// Aimed at a transfer's deadline, the alarm is set when the deadline moves, not while it
    /// stays; once due, aiming at the same deadline sets it again (a timeout handled, the
    /// transfer may keep its deadline).
    #[test]
    fn an_aimed_alarm_is_set_only_when_its_deadline_moves_or_came() {
        let ms = Duration::from_millis;
        let mut alarm = Fixed { due: true, sets: 0 };
        let mut aimed = Aimed::new(&mut alarm);
        aimed.aim(ms(100), ms(0));
        aimed.aim(ms(100), ms(10));
        aimed.aim(ms(150), ms(20));
        assert_eq!(poll_once(aimed.due()), Poll::Ready(()));
        aimed.aim(ms(150), ms(150));
        assert_eq!(alarm.sets, 3);
    }
}
