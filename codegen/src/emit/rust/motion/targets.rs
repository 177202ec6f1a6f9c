//! `run_at_velocity` (profile velocity) and `apply_torque` (profile torque), each generated only
//! where the modes enum lists the mode and the description has its objects, with their async
//! twins `run_at_velocity_async` and `apply_torque_async`.

use proc_macro2::{Ident, TokenStream};
use quote::quote;

use super::{
    async_time, lists_mode, marker, modes, object, Items, Shared, PROFILE_TORQUE, PROFILE_VELOCITY,
};
use crate::ir::{DataType, Device};

/// The profile velocity and torque impls and methods of `handle`.
pub(super) fn emit(device: &Device, handle: &Ident, control: &Ident, status: &Ident) -> Items {
    let Some((request, display)) = modes(device) else {
        return Items::default();
    };
    let shared = |actual: Ident| Shared {
        handle,
        control,
        status,
        request: request.clone(),
        display: display.clone(),
        actual,
    };
    let mut items = velocity(device, handle, &shared);
    items.extend(torque(device, handle, status, &shared));
    items
}

fn velocity<'a>(device: &Device, handle: &Ident, shared: &impl Fn(Ident) -> Shared<'a>) -> Items {
    if !lists_mode(device, PROFILE_VELOCITY) {
        return Items::default();
    }
    let target = object(device, 0x60FF, 0, DataType::Signed(4));
    let actual = object(device, 0x606C, 0, DataType::Signed(4));
    let (Some(target), Some(actual)) = (target, actual) else {
        return Items::default();
    };
    let (target, actual) = (marker(target), marker(actual));
    let shared = shared(actual.clone());
    let (header, async_header) = shared.headers(&target, &TokenStream::new());
    let time = async_time();
    Items {
        blocking: quote! {
            impl<L> ::drivebus::control::ProfileVelocityObjects for #handle<L> {
                type TargetVelocity = params::#target;
                type VelocityActual = params::#actual;
            }

            #header
            {
                /// Profile velocity: switches to profile velocity mode, writes the target velocity
                /// (raw, in the drive's velocity units), clears halt and waits for target reached
                /// (statusword bit 10) until `deadline`; returns the velocity actual value. The axis
                /// goes on at that velocity. Refused before anything is sent when the drive is not
                /// operation enabled; a maximum slippage error or time out halts the axis and is
                /// returned. The accelerations are the drive's (set them through their accessors).
                pub fn run_at_velocity(&mut self, velocity: i32, deadline: ::drivebus::control::driver::Instant) -> Result<i32, ::drivebus::control::motion_error::MotionError> {
                    ::drivebus::control::motion_driver::run_at_velocity::<Self, L>(&mut self.device, velocity, deadline)
                }
            }
        },
        awaited: quote! {
            #async_header
            {
                /// `run_at_velocity` awaited: the same change of velocity, refusals and errors,
                /// polling on `timer` for at most `limit` (a time out halts the axis first).
                pub async fn run_at_velocity_async(&mut self, velocity: i32, #time) -> Result<i32, ::drivebus::control::motion_error::MotionError> {
                    ::drivebus::control::async_motion_driver::run_at_velocity::<Self, L>(&mut self.device, velocity, timer, limit).await
                }
            }
        },
    }
}

fn torque<'a>(
    device: &Device,
    handle: &Ident,
    status: &Ident,
    shared: &impl Fn(Ident) -> Shared<'a>,
) -> Items {
    if !lists_mode(device, PROFILE_TORQUE) {
        return Items::default();
    }
    let Some(target) = object(device, 0x6071, 0, DataType::Signed(2)) else {
        return Items::default();
    };
    let target = marker(target);
    // Profile torque reads nothing back but the statusword, which the header already asks for.
    let shared = shared(status.clone());
    let (header, async_header) = shared.headers(&target, &TokenStream::new());
    let time = async_time();
    Items {
        blocking: quote! {
            impl<L> ::drivebus::control::ProfileTorqueObjects for #handle<L> {
                type TargetTorque = params::#target;
            }

            #header
            {
                /// Profile torque: switches to profile torque mode, writes the target torque (raw,
                /// in the drive's torque units), clears halt and waits for target reached
                /// (statusword bit 10) until `deadline`. Refused before anything is sent when the
                /// drive is not operation enabled; a time out halts the axis and is returned. The
                /// torque slope is the drive's.
                pub fn apply_torque(&mut self, torque: i16, deadline: ::drivebus::control::driver::Instant) -> Result<(), ::drivebus::control::motion_error::MotionError> {
                    ::drivebus::control::motion_driver::apply_torque::<Self, L>(&mut self.device, torque, deadline)
                }
            }
        },
        awaited: quote! {
            #async_header
            {
                /// `apply_torque` awaited: the same torque, refusals and errors, polling on
                /// `timer` for at most `limit` (a time out halts the axis first).
                pub async fn apply_torque_async(&mut self, torque: i16, #time) -> Result<(), ::drivebus::control::motion_error::MotionError> {
                    ::drivebus::control::async_motion_driver::apply_torque::<Self, L>(&mut self.device, torque, timer, limit).await
                }
            }
        },
    }
}
