//! `run_at_velocity` (profile velocity) and `apply_torque` (profile torque), each generated only
//! where the modes enum lists the mode and the description has its objects.

use proc_macro2::{Ident, TokenStream};
use quote::quote;

use super::{lists_mode, marker, modes, object, Shared, PROFILE_TORQUE, PROFILE_VELOCITY};
use crate::ir::{DataType, Device};

/// The profile velocity and torque impls and methods of `handle`.
pub(super) fn emit(
    device: &Device,
    handle: &Ident,
    control: &Ident,
    status: &Ident,
) -> TokenStream {
    let Some((request, display)) = modes(device) else {
        return TokenStream::new();
    };
    let shared = |actual: Ident| Shared {
        handle,
        control,
        status,
        request: request.clone(),
        display: display.clone(),
        actual,
    };
    let velocity = velocity(device, handle, &shared);
    let torque = torque(device, handle, status, &shared);
    quote! {
        #velocity
        #torque
    }
}

fn velocity<'a>(
    device: &Device,
    handle: &Ident,
    shared: &impl Fn(Ident) -> Shared<'a>,
) -> TokenStream {
    if !lists_mode(device, PROFILE_VELOCITY) {
        return TokenStream::new();
    }
    let target = object(device, 0x60FF, 0, DataType::Signed(4));
    let actual = object(device, 0x606C, 0, DataType::Signed(4));
    let (Some(target), Some(actual)) = (target, actual) else {
        return TokenStream::new();
    };
    let (target, actual) = (marker(target), marker(actual));
    let header = shared(actual.clone()).header(&target, TokenStream::new());
    quote! {
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
    }
}

fn torque<'a>(
    device: &Device,
    handle: &Ident,
    status: &Ident,
    shared: &impl Fn(Ident) -> Shared<'a>,
) -> TokenStream {
    if !lists_mode(device, PROFILE_TORQUE) {
        return TokenStream::new();
    }
    let Some(target) = object(device, 0x6071, 0, DataType::Signed(2)) else {
        return TokenStream::new();
    };
    let target = marker(target);
    // Profile torque reads nothing back but the statusword, which the header already asks for.
    let header = shared(status.clone()).header(&target, TokenStream::new());
    quote! {
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
    }
}
