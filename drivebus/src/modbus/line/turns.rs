//! Turns on a shared line, first come first served: a FIFO ticket queue that threads and async
//! tasks wait in alike (a thread waits by parking, see [`super::park`]). A plain `Mutex` lets
//! the thread that just released it take it again before a sleeping waiter wakes up, so a
//! handle polling in a tight loop could starve the others; here a released turn is handed
//! straight to the oldest waiter.
//!
//! Runtime-agnostic: the waiting is a `Waker`, whatever executor made it.

use core::future::Future;
use core::pin::Pin;
use core::task::{Context, Poll, Waker};
use std::collections::VecDeque;
use std::sync::{Mutex, MutexGuard, PoisonError};

/// The queue of one line: who holds it, who waits, whether it is closed.
#[derive(Debug, Default)]
pub(super) struct Turns {
    state: Mutex<State>,
}

#[derive(Debug, Default)]
struct State {
    /// The ticket the next arrival gets.
    next: u64,
    /// The ticket holding the line.
    holder: Option<u64>,
    /// Waiting tickets, oldest first.
    waiting: VecDeque<Waiting>,
    /// Closed: no turn is handed out any more.
    closed: bool,
}

#[derive(Debug)]
struct Waiting {
    ticket: u64,
    waker: Waker,
}

/// The line held; dropping it hands the line to the oldest waiter.
#[derive(Debug)]
pub(super) struct Turn<'a> {
    turns: &'a Turns,
    ticket: u64,
}

impl Drop for Turn<'_> {
    fn drop(&mut self) {
        self.turns.release(self.ticket);
    }
}

/// Why no turn was given: the line was closed before this waiter's turn came.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Closed;

impl Turns {
    /// The state; a panic elsewhere never leaves it half-updated (every update is a few
    /// assignments that cannot panic), so a poisoned lock is still consistent.
    fn state(&self) -> MutexGuard<'_, State> {
        self.state.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// Waits for this caller's turn, behind everyone already waiting.
    pub(super) fn take(&self) -> TakeTurn<'_> {
        TakeTurn {
            turns: self,
            ticket: None,
            done: false,
        }
    }

    /// Closes the line: every waiter, and every later caller, gets [`Closed`]. The current
    /// holder finishes its request.
    pub(super) fn close(&self) {
        let waiting = {
            let mut state = self.state();
            state.closed = true;
            core::mem::take(&mut state.waiting)
        };
        for waiter in waiting {
            waiter.waker.wake();
        }
    }

    /// Whether [`close`](Self::close) was called.
    pub(super) fn is_closed(&self) -> bool {
        self.state().closed
    }

    /// How many wait for the line.
    #[cfg(test)]
    pub(super) fn waiting(&self) -> usize {
        self.state().waiting.len()
    }

    /// Hands the line from `ticket` to the oldest waiter, or frees it.
    fn release(&self, ticket: u64) {
        let next = {
            let mut state = self.state();
            if state.holder != Some(ticket) {
                return;
            }
            let next = state.waiting.pop_front();
            state.holder = next.as_ref().map(|w| w.ticket);
            next
        };
        if let Some(next) = next {
            next.waker.wake();
        }
    }
}

/// The future of [`Turns::take`]. Dropped while waiting, it leaves the queue; dropped after
/// the line was handed to it but before it was polled again, it hands the line on.
#[derive(Debug)]
pub(super) struct TakeTurn<'a> {
    turns: &'a Turns,
    ticket: Option<u64>,
    done: bool,
}

impl<'a> Future for TakeTurn<'a> {
    type Output = Result<Turn<'a>, Closed>;

    fn poll(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<Self::Output> {
        let turns = self.turns;
        let mut state = turns.state();
        let outcome = match self.ticket {
            None => arrive(&mut state, cx.waker()),
            Some(ticket) => wait(&mut state, ticket, cx.waker()),
        };
        drop(state);
        match outcome {
            Step::Waiting(ticket) => {
                self.ticket = Some(ticket);
                Poll::Pending
            }
            Step::Holding(ticket) => {
                self.done = true;
                Poll::Ready(Ok(Turn { turns, ticket }))
            }
            Step::Closed => {
                self.done = true;
                Poll::Ready(Err(Closed))
            }
        }
    }
}

/// Where one poll of a [`TakeTurn`] left it.
enum Step {
    Waiting(u64),
    Holding(u64),
    Closed,
}

/// A first poll: take a ticket; hold the line at once if it is free and nobody waits.
fn arrive(state: &mut State, waker: &Waker) -> Step {
    if state.closed {
        return Step::Closed;
    }
    let ticket = state.next;
    state.next += 1;
    if state.holder.is_none() {
        state.holder = Some(ticket);
        return Step::Holding(ticket);
    }
    state.waiting.push_back(Waiting {
        ticket,
        waker: waker.clone(),
    });
    Step::Waiting(ticket)
}

/// A later poll: the line was handed over, or it is still someone else's, or the waiter was
/// sent away by [`Turns::close`].
fn wait(state: &mut State, ticket: u64, waker: &Waker) -> Step {
    if state.closed {
        // Handed the line just before the close: it gives it up unused (nobody waits any more).
        if state.holder == Some(ticket) {
            state.holder = None;
        }
        return Step::Closed;
    }
    if state.holder == Some(ticket) {
        return Step::Holding(ticket);
    }
    match state.waiting.iter_mut().find(|w| w.ticket == ticket) {
        Some(waiting) => {
            waiting.waker.clone_from(waker);
            Step::Waiting(ticket)
        }
        None => Step::Closed,
    }
}

impl Drop for TakeTurn<'_> {
    fn drop(&mut self) {
        let Some(ticket) = self.ticket.filter(|_| !self.done) else {
            return;
        };
        let handed_over = {
            let mut state = self.turns.state();
            state.waiting.retain(|w| w.ticket != ticket);
            state.holder == Some(ticket)
        };
        if handed_over {
            self.turns.release(ticket);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::pin::pin;
    use std::sync::Arc;
    use std::task::Wake;
    use std::vec::Vec;

    /// Counts its wakes.
    #[derive(Default)]
    struct Count(std::sync::atomic::AtomicUsize);

    impl Wake for Count {
        fn wake(self: Arc<Self>) {
            self.0.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
        }
    }

    fn poll<F: Future + Unpin>(future: &mut F, waker: &Waker) -> Poll<F::Output> {
        Pin::new(future).poll(&mut Context::from_waker(waker))
    }

    #[test]
    fn a_released_turn_goes_to_the_oldest_waiter_not_to_a_newcomer() {
        let turns = Turns::default();
        let count = Arc::new(Count::default());
        let waker = Waker::from(Arc::clone(&count));
        let first = match poll(&mut turns.take(), &waker) {
            Poll::Ready(Ok(turn)) => turn,
            other => panic!("a free line is held at once: {other:?}"),
        };
        let mut second = turns.take();
        assert!(poll(&mut second, &waker).is_pending());
        drop(first);
        assert_eq!(count.0.load(std::sync::atomic::Ordering::SeqCst), 1);
        // The releasing caller comes straight back: it queues behind the woken waiter.
        let mut again = turns.take();
        assert!(poll(&mut again, &waker).is_pending(), "no barging");
        let second = match poll(&mut second, &waker) {
            Poll::Ready(Ok(turn)) => turn,
            other => panic!("the oldest waiter holds the line: {other:?}"),
        };
        drop(second);
        assert!(matches!(poll(&mut again, &waker), Poll::Ready(Ok(_))));
    }

    #[test]
    fn a_waiter_dropped_after_the_handover_passes_the_line_on() {
        let turns = Turns::default();
        let waker = Waker::from(Arc::new(Count::default()));
        let first = pin!(turns.take())
            .as_mut()
            .poll(&mut Context::from_waker(&waker));
        let mut second = turns.take();
        let mut third = turns.take();
        assert!(poll(&mut second, &waker).is_pending());
        assert!(poll(&mut third, &waker).is_pending());
        drop(first);
        drop(second);
        assert!(matches!(poll(&mut third, &waker), Poll::Ready(Ok(_))));
    }

    #[test]
    fn a_waiter_handed_the_line_just_before_the_close_is_sent_away_too() {
        let turns = Turns::default();
        let waker = Waker::from(Arc::new(Count::default()));
        let first = poll(&mut turns.take(), &waker);
        let mut second = turns.take();
        assert!(poll(&mut second, &waker).is_pending());
        drop(first);
        turns.close();
        assert!(matches!(
            poll(&mut second, &waker),
            Poll::Ready(Err(Closed))
        ));
        assert_eq!(turns.state().holder, None);
    }

    #[test]
    fn closing_sends_every_waiter_away_and_refuses_newcomers() {
        let turns = Turns::default();
        let count = Arc::new(Count::default());
        let waker = Waker::from(Arc::clone(&count));
        let holder = poll(&mut turns.take(), &waker);
        let mut waiters: Vec<_> = (0..3).map(|_| turns.take()).collect();
        for waiter in &mut waiters {
            assert!(poll(waiter, &waker).is_pending());
        }
        turns.close();
        assert_eq!(count.0.load(std::sync::atomic::Ordering::SeqCst), 3);
        for waiter in &mut waiters {
            assert!(matches!(poll(waiter, &waker), Poll::Ready(Err(Closed))));
        }
        assert!(matches!(
            poll(&mut turns.take(), &waker),
            Poll::Ready(Err(Closed))
        ));
        drop(holder);
        assert!(turns.is_closed());
    }
}
