//! The events around a trigger: a ring buffer of the last `pre` events, then the trigger's own,
//! then the next `post` events. A trigger while the events after another are being collected
//! belongs to that capture (a scope's holdoff); the next one after it starts a new capture.

use std::collections::VecDeque;
use std::vec::Vec;

/// A captured window.
#[derive(Debug, Clone, PartialEq)]
pub struct Captured<T> {
    /// Up to `pre` events before the trigger, oldest first.
    pub before: Vec<T>,
    /// The event that fired the trigger.
    pub trigger: T,
    /// Up to `post` events after it.
    pub after: Vec<T>,
    /// False when the input ended before `post` events came after the trigger.
    pub complete: bool,
}

/// A pre- and post-trigger window over a stream of events.
#[derive(Debug, Clone)]
pub struct Window<T> {
    pre: usize,
    post: usize,
    before: VecDeque<T>,
    capturing: Option<Captured<T>>,
}

impl<T> Window<T> {
    /// Keeps `pre` events before a trigger and `post` after it.
    pub fn new(pre: usize, post: usize) -> Self {
        Self {
            pre,
            post,
            before: VecDeque::with_capacity(pre + 1),
            capturing: None,
        }
    }

    /// Takes the next event, `fired` if it fired the trigger; returns a window once its last
    /// event came.
    pub fn push(&mut self, event: T, fired: bool) -> Option<Captured<T>> {
        if let Some(capture) = &mut self.capturing {
            capture.after.push(event);
            return (capture.after.len() >= self.post)
                .then(|| self.capturing.take())
                .flatten();
        }
        if !fired {
            if self.pre > 0 {
                if self.before.len() == self.pre {
                    self.before.pop_front();
                }
                self.before.push_back(event);
            }
            return None;
        }
        let capture = Captured {
            before: self.before.drain(..).collect(),
            trigger: event,
            after: Vec::with_capacity(self.post),
            complete: true,
        };
        if self.post == 0 {
            return Some(capture);
        }
        self.capturing = Some(capture);
        None
    }

    /// The input ended: the window still collecting events after its trigger, if any, marked
    /// incomplete.
    pub fn finish(self) -> Option<Captured<T>> {
        self.capturing.map(|c| Captured {
            complete: false,
            ..c
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::vec;

    #[test]
    fn a_window_keeps_pre_and_post_events_around_its_trigger() {
        let mut window = Window::new(2, 2);
        let fired = |n: u32| n == 5 || n == 6 || n == 12;
        let mut captured = Vec::new();
        for n in 0..14 {
            captured.extend(window.push(n, fired(n)));
        }
        captured.extend(window.finish());
        assert_eq!(
            captured,
            [
                Captured {
                    before: vec![3, 4],
                    trigger: 5,
                    after: vec![6, 7],
                    complete: true
                },
                Captured {
                    before: vec![10, 11],
                    trigger: 12,
                    after: vec![13],
                    complete: false
                },
            ],
            "6 fired while 5's window was collecting: it belongs to that window"
        );
    }

    #[test]
    fn without_post_events_a_window_is_done_at_its_trigger() {
        let mut window = Window::new(0, 0);
        assert_eq!(window.push('a', false), None);
        assert_eq!(
            window.push('b', true),
            Some(Captured {
                before: vec![],
                trigger: 'b',
                after: vec![],
                complete: true
            })
        );
        assert_eq!(window.finish(), None);
    }
}
