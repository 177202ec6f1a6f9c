//! Drive control: pure state-machine planners and, with `std`, a blocking driver.
//!
//! The core is `no_std`, allocates nothing and reads no clock: the caller passes the decoded
//! status word and the time, the planner answers with the next command to send, a reason to wait,
//! or why the target cannot be reached.
//!
//! * [`machine`] — a state machine as data (states recognised from status bits, transitions caused
//!   by command writes) and the planner that walks it. Vendor machines (Lafert Smartris Modbus mode)
//!   are emitted by drivegen as such tables.
//! * [`cia402`] — the CiA 402 power drive system machine as a [`machine::Machine`] table, plus the
//!   rules tables cannot express: fault reset on a rising edge, halt, safe torque off, voltage and
//!   remote bits.
//! * [`quirks`] — how real drives deviate from CiA 402, declared in descriptions.
//! * `device` (feature `server`) — the device side of CiA 402 (transitions a controlword takes,
//!   the statusword of each state): the simulator's CiA 402 behaviour and the test double of masters.
//! * [`mode`] — changing the mode of operation (0x6060) and confirming it (0x6061).
//! * [`mode_bits`] — the controlword and statusword bits of profile position and homing.
//! * [`position`] and [`homing`] — a profile position move and a homing run as pure planners
//!   (set-point handshake, target reached, following and homing errors).
//! * [`profile_target`] — a new target in profile velocity or profile torque as a pure planner
//!   (halt cleared, target reached, maximum slippage).
//! * `motion_driver` and `motion_error` (std) — their blocking shell behind `drive.move_to(..)`,
//!   `drive.home(..)`, `drive.run_at_velocity(..)` and `drive.apply_torque(..)`, and its typed
//!   errors.
//! * `motion_poll` (std) — the refusals and steps both motion shells take; `async_motion_driver`
//!   (features `async` and `std`) — the async shell over them.
//! * [`cyclic`] — the cyclic synchronous modes (csp, csv, cst) as a pure planner per axis: the
//!   RPDO content for each SYNC from the TPDO feedback and the next trajectory sample.
//! * `cyclic_driver` (feature `canopen`) — its blocking shell on the network manager: SYNC
//!   producer, RPDOs sent, TPDOs subscribed, cycle timing measured; `async_cyclic_driver`
//!   (features `async` and `canopen`) — the same run on the async network manager. Both take
//!   their decisions from `cyclic_steps` (the axes from the drives' answers, each cycle).
//! * [`stop_option`] — what the option codes (605Ah-605Eh) say: how a stop brakes and where a
//!   quick stop ends.
//! * [`objects`] — the traits generated crates implement to hand their parameters to the driver.
//! * [`walk`] — what a driver decides between two polls (the next command, or the error a
//!   deadline ends the walk with), without I/O: the steps both drivers take.
//! * `driver` (std) — the blocking driver behind `drive.enable_operation(deadline)`.
//! * `async_driver` (feature `async`) — the async driver behind
//!   `drive.enable_operation_async(&timer, limit).await`, waiting only through an
//!   [`asynch::Timer`](crate::asynch::Timer).

#[cfg(all(feature = "async", feature = "canopen"))]
pub mod async_cyclic_driver;
#[cfg(feature = "async")]
pub mod async_driver;
#[cfg(all(feature = "async", feature = "std"))]
pub mod async_motion_driver;
pub mod cia402;
mod control_error;
#[cfg(feature = "std")]
pub mod cycle_stats;
pub mod cyclic;
#[cfg(feature = "canopen")]
pub mod cyclic_driver;
#[cfg(feature = "canopen")]
mod cyclic_steps;
#[cfg(feature = "server")]
pub mod device;
#[cfg(feature = "std")]
pub mod driver;
pub use drivebus_model::control::machine;
pub mod homing;
pub mod mode;
pub use drivebus_model::control::mode_bits;
#[cfg(feature = "std")]
pub mod motion_driver;
#[cfg(feature = "std")]
pub mod motion_error;
#[cfg(feature = "std")]
pub mod motion_poll;
pub mod objects;
pub mod objects_on;
pub mod position;
pub mod profile_target;
pub use drivebus_model::control::quirks;
pub mod stop_option;
pub mod walk;

pub use cia402::{Blocker, Cia402Planner, State, Step, Target, Waiting};
pub use control_error::{ControlError, StuckReason};
pub use machine::{Machine, Plan, StateDef, StatePattern, TransitionDef, TransitionKind};
pub use objects::{
    Cia402Modes, Cia402Objects, HomingObjects, ProfilePositionObjects, ProfileTorqueObjects,
    ProfileVelocityObjects, QuickStopOptionObjects, VendorMachine,
};
pub use quirks::{Quirk, Quirks};

/// A monotonic time in milliseconds, from any epoch the caller chooses; the core has no clock.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Default)]
pub struct Millis(pub u64);

impl Millis {
    /// Milliseconds elapsed since `earlier` (0 if `earlier` is later).
    pub fn since(self, earlier: Millis) -> u64 {
        self.0.saturating_sub(earlier.0)
    }
}
