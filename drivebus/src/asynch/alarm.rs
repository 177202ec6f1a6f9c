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

/// Completes once `alarm` is due: a kept alarm raced against other work (a transfer that
/// waits for frames and its deadline alike) without giving it up.
#[cfg_attr(not(feature = "canopen"), allow(dead_code))]
pub(crate) fn due<A: Alarm + ?Sized>(alarm: &mut A) -> impl Future<Output = ()> + '_ {
    poll_fn(move |cx| alarm.poll_due(cx))
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
}
