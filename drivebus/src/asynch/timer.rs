//! [`Timer`], the async API's one source of time, and [`within`], a timeout over any future.

use core::future::{poll_fn, Future};
use core::pin::pin;
use core::task::Poll;
use core::time::Duration;

use super::Alarm;

/// Waits on behalf of the async API: request timeouts, the RTU inter-frame silence, retries.
/// tokio's timer implements it behind feature `tokio`; an embassy or test timer implements it
/// in a few lines.
#[allow(async_fn_in_trait)]
pub trait Timer {
    /// The deadline a client keeps for its request timeouts (see [`Alarm`]).
    type Alarm: Alarm;

    /// A new alarm, not set yet.
    fn alarm(&self) -> Self::Alarm;

    /// Completes once `duration` has passed.
    async fn sleep(&self, duration: Duration);
}

impl<T: Timer + ?Sized> Timer for &T {
    type Alarm = T::Alarm;

    fn alarm(&self) -> T::Alarm {
        (**self).alarm()
    }

    async fn sleep(&self, duration: Duration) {
        (**self).sleep(duration).await;
    }
}

/// The time given to [`within`] ran out before the work completed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Elapsed;

/// Runs `work` for at most `limit` of `timer`'s time. Whichever completes first wins; on
/// [`Elapsed`] the work's future has been dropped, so its cancellation handling has run.
pub async fn within<T>(
    timer: &impl Timer,
    limit: Duration,
    work: impl Future<Output = T>,
) -> Result<T, Elapsed> {
    let mut work = pin!(work);
    let mut deadline = pin!(timer.sleep(limit));
    // The work is polled first: an answer that is ready when the time runs out still counts.
    poll_fn(|cx| {
        if let Poll::Ready(value) = work.as_mut().poll(cx) {
            return Poll::Ready(Ok(value));
        }
        deadline.as_mut().poll(cx).map(|()| Err(Elapsed))
    })
    .await
}

#[cfg(feature = "tokio")]
mod tokio_timer {
    use core::future::Future;
    use core::pin::Pin;
    use core::task::{Context, Poll};
    use core::time::Duration;

    use std::boxed::Box;

    use tokio::time::{Instant, Sleep};

    /// tokio's timer (`tokio::time::sleep`): needs a tokio runtime with time enabled.
    #[derive(Debug, Clone, Copy, Default)]
    pub struct TokioTimer;

    impl super::Timer for TokioTimer {
        type Alarm = TokioAlarm;

        fn alarm(&self) -> TokioAlarm {
            TokioAlarm::default()
        }

        async fn sleep(&self, duration: Duration) {
            tokio::time::sleep(duration).await;
        }
    }

    /// tokio's [`Alarm`](super::Alarm): one `tokio::time::Sleep`, made at the first `set`
    /// (so the alarm can be made outside a runtime) and `reset` at every later one, which is
    /// an atomic store while the deadline only moves later. Like a tokio stream, it belongs to
    /// the runtime it was first used in.
    #[derive(Debug, Default)]
    pub struct TokioAlarm(Option<Pin<Box<Sleep>>>);

    /// How far a deadline beyond `Instant`'s range is put: tokio's own "far future".
    const FAR_FUTURE: Duration = Duration::from_secs(86_400 * 365 * 30);

    impl super::Alarm for TokioAlarm {
        fn set(&mut self, after: Duration) {
            let now = Instant::now();
            let deadline = now.checked_add(after).unwrap_or(now + FAR_FUTURE);
            match &mut self.0 {
                Some(sleep) => sleep.as_mut().reset(deadline),
                None => self.0 = Some(Box::pin(tokio::time::sleep_until(deadline))),
            }
        }

        fn poll_due(&mut self, cx: &mut Context<'_>) -> Poll<()> {
            match &mut self.0 {
                Some(sleep) => sleep.as_mut().poll(cx),
                None => Poll::Pending,
            }
        }
    }
}

#[cfg(feature = "tokio")]
pub use tokio_timer::{TokioAlarm, TokioTimer};

#[cfg(test)]
mod tests {
    use super::*;
    use core::task::{Context, Waker};

    /// A timer whose sleep is over at once, or never.
    struct Instant(bool);

    /// `Instant`'s alarm: due at once, or never.
    struct InstantAlarm(bool);

    impl Alarm for InstantAlarm {
        fn set(&mut self, _: Duration) {}

        fn poll_due(&mut self, _: &mut Context<'_>) -> Poll<()> {
            match self.0 {
                true => Poll::Ready(()),
                false => Poll::Pending,
            }
        }
    }

    impl Timer for Instant {
        type Alarm = InstantAlarm;

        fn alarm(&self) -> InstantAlarm {
            InstantAlarm(self.0)
        }

        async fn sleep(&self, _: Duration) {
            if !self.0 {
                core::future::pending::<()>().await;
            }
        }
    }

    fn poll_once<F: Future>(future: F) -> Poll<F::Output> {
        let mut cx = Context::from_waker(Waker::noop());
        pin!(future).poll(&mut cx)
    }

    #[test]
    fn ready_work_wins_even_when_the_time_is_up() {
        let outcome = poll_once(within(&Instant(true), Duration::ZERO, async { 7 }));
        assert_eq!(outcome, Poll::Ready(Ok(7)));
    }

    #[test]
    fn pending_work_ends_in_elapsed_when_the_time_is_up() {
        let work = core::future::pending::<u8>();
        assert_eq!(
            poll_once(within(&Instant(true), Duration::ZERO, work)),
            Poll::Ready(Err(Elapsed))
        );
    }

    #[test]
    fn pending_work_waits_while_there_is_time() {
        let work = core::future::pending::<u8>();
        assert_eq!(
            poll_once(within(&Instant(false), Duration::ZERO, work)),
            Poll::Pending
        );
    }
}
