//! The CiA 402 objects as one protocol carries them: each trait names, once, which of a drive's
//! objects a driver procedure reads and writes over protocol `P`, so the blocking, motion and
//! async drivers bound `O: ProfilePositionOn<L::Protocol>` instead of repeating a line per
//! object. Each is implemented for every type whose objects can be read and written so (a
//! blanket impl): a generated handle needs nothing more than its object traits.

use super::objects::{
    Cia402Modes, Cia402Objects, HomingObjects, ProfilePositionObjects, ProfileTorqueObjects,
    ProfileVelocityObjects, QuickStopOptionObjects,
};
use crate::parameter::{Readable, Writable};
use crate::Protocol;

/// A bound alias: the trait `$name<P>` with `$bounds` as its supertraits, and its blanket impl
/// for every type that meets them (written once, so the two cannot drift apart).
macro_rules! bound_alias {
    ($(#[$doc:meta])* $name:ident: $($bounds:tt)+) => {
        $(#[$doc])*
        pub trait $name<P: Protocol>: $($bounds)+ {}

        impl<P: Protocol, O: $($bounds)+ + ?Sized> $name<P> for O {}
    };
}

bound_alias! {
    /// The controlword read and written and the statusword read over `P`: what moving an
    /// enabled axis needs.
    ControlOn: Cia402Objects<Controlword: Readable<P> + Writable<P>, Statusword: Readable<P>>
}

bound_alias! {
    /// [`ControlOn`], and the safe torque off word read: what walking the state machine needs.
    WalkOn: ControlOn<P> + Cia402Objects<SafeTorqueOffWord: Readable<P>>
}

bound_alias! {
    /// [`WalkOn`], and the quick stop option code (605Ah) read: a quick stop seen through to the
    /// end the drive's own code gives.
    QuickStopOptionOn: WalkOn<P> + QuickStopOptionObjects<QuickStopOptionCode: Readable<P>>
}

bound_alias! {
    /// The controlword read and written, the mode of operation written and its display read:
    /// what changing the mode needs.
    ModeOn: Cia402Modes<
        Controlword: Readable<P> + Writable<P>,
        ModesOfOperation: Writable<P>,
        ModesOfOperationDisplay: Readable<P>,
    >
}

bound_alias! {
    /// [`ControlOn`] and [`ModeOn`], the target position written and the position read: a
    /// profile position move.
    ProfilePositionOn: ControlOn<P>
        + ModeOn<P>
        + ProfilePositionObjects<TargetPosition: Writable<P>, PositionActual: Readable<P>>
}

bound_alias! {
    /// [`ControlOn`] and [`ModeOn`], the homing method written and the position read: a homing
    /// run.
    HomingOn: ControlOn<P>
        + ModeOn<P>
        + HomingObjects<HomingMethod: Writable<P>>
        + ProfilePositionObjects<PositionActual: Readable<P>>
}

bound_alias! {
    /// [`ControlOn`] and [`ModeOn`], the target velocity written and the velocity read: profile
    /// velocity.
    ProfileVelocityOn: ControlOn<P>
        + ModeOn<P>
        + ProfileVelocityObjects<TargetVelocity: Writable<P>, VelocityActual: Readable<P>>
}

bound_alias! {
    /// [`ControlOn`] and [`ModeOn`], the target torque written: profile torque.
    ProfileTorqueOn: ControlOn<P> + ModeOn<P> + ProfileTorqueObjects<TargetTorque: Writable<P>>
}
