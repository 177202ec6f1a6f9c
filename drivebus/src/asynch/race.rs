//! Two small future combinators the async client needs, executor-free.

use core::future::{poll_fn, Future};
use core::pin::{pin, Pin};
use core::task::Poll;

/// Which of two futures completed first.
#[cfg_attr(not(feature = "canopen"), allow(dead_code))]
pub(crate) enum First<A, B> {
    /// The first one.
    A(A),
    /// The second one.
    B(B),
}

/// Polls `a`, then `b`, until one completes; `a` wins a tie. `a` is dropped if `b` wins, so it
/// must be cancel-safe; `b` is borrowed and may be polled again later.
#[cfg_attr(not(feature = "canopen"), allow(dead_code))]
pub(crate) async fn first<A: Future, B: Future>(
    a: A,
    mut b: Pin<&mut B>,
) -> First<A::Output, B::Output> {
    let mut a = pin!(a);
    poll_fn(|cx| {
        if let Poll::Ready(value) = a.as_mut().poll(cx) {
            return Poll::Ready(First::A(value));
        }
        b.as_mut().poll(cx).map(First::B)
    })
    .await
}

/// What `work` gives at its first poll, or `None` (then it is dropped, so it must be
/// cancel-safe): what is there now, without waiting.
pub(crate) async fn ready_now<F: Future>(work: F) -> Option<F::Output> {
    let mut work = pin!(work);
    match poll_fn(|cx| Poll::Ready(work.as_mut().poll(cx))).await {
        Poll::Ready(value) => Some(value),
        Poll::Pending => None,
    }
}
