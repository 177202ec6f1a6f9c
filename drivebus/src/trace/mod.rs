//! Triggered capture of a bus trace, as a scope keeps it: a [`Trigger`] says which event starts a
//! capture (a parameter crossing a level, an EMCY, an NMT state change) and a [`Window`] keeps
//! the events just before it from a ring buffer and the events just after it. Both are sans-I/O
//! and know nothing of frames: the caller decodes frames into [`Event`]s.

mod trigger;
mod window;

pub use trigger::{Armed, Crossing, Event, Trigger, TriggerError};
pub use window::{Captured, Window};
