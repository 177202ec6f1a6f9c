//! Drive control tables: a state machine as data with its pure planner ([`machine`]), and the
//! ways real drives deviate from CiA 402 ([`quirks`]). The blocking driver and the CiA 402 rules
//! tables cannot express are in `drivebus::control`.

pub mod machine;
pub mod mode_bits;
pub mod quirks;

pub use machine::{Machine, Plan, StateDef, StatePattern, TransitionDef, TransitionKind};
pub use quirks::{Quirk, Quirks};
