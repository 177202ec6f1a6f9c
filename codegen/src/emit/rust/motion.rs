//! Motion procedures on the handle, generated only where the description has their objects
//! (issue 32): `move_to` when the modes enum lists profile position (1) and the drive has the
//! target position (607Ah) and a position actual value (6064h, else 6063h); `home` when the
//! modes list homing (6) and the homing method (6098h) is an enum of the methods the drive
//! lists; `run_at_velocity` when the modes list profile velocity (3) and the drive has the
//! target velocity (60FFh) and the velocity actual value (606Ch); `apply_torque` when the modes
//! list profile torque (4) and the drive has the target torque (6071h). A drive without them has
//! no such method: calling it does not compile.

use drivebus_model::control::mode_bits::{
    HOMING, PROFILE_POSITION, PROFILE_TORQUE, PROFILE_VELOCITY,
};
use proc_macro2::{Ident, TokenStream};
use quote::quote;

use super::ident;

mod targets;
use crate::ir::{DataType, Device, Parameter};
use crate::names;

/// The parameter at CANopen object `index`, `subindex`, of type `data_type`.
fn object(device: &Device, index: u16, subindex: u8, data_type: DataType) -> Option<&Parameter> {
    device.parameters.iter().find(|p| {
        p.data_type == data_type
            && p.canopen
                .iter()
                .any(|a| a.index == index && a.subindex == subindex)
    })
}

fn marker(parameter: &Parameter) -> Ident {
    ident(&names::camel(&parameter.name))
}

/// Whether the description's modes enum (that of 6060h) lists `mode`.
fn lists_mode(device: &Device, mode: i8) -> bool {
    object(device, 0x6060, 0, DataType::Signed(1))
        .and_then(|p| p.enumeration.as_deref())
        .and_then(|name| device.enumeration(name))
        .is_some_and(|e| e.values.iter().any(|v| v.value == i64::from(mode)))
}

/// The software position limits (607Dh sub 1 and 2) as the expression the methods read them
/// with, and the bounds that needs; `None` when the drive has no limits.
fn limits(device: &Device) -> (TokenStream, TokenStream) {
    let sub = |s| object(device, 0x607D, s, DataType::Signed(4)).map(marker);
    match (sub(1), sub(2)) {
        (Some(a), Some(b)) => (
            quote! {
                ::drivebus::control::position::SoftLimits::between(
                    self.device.read_raw::<params::#a>()?,
                    self.device.read_raw::<params::#b>()?,
                )
            },
            quote! {
                params::#a: ::drivebus::Readable<L::Protocol>,
                params::#b: ::drivebus::Readable<L::Protocol>,
            },
        ),
        _ => (quote! { None }, TokenStream::new()),
    }
}

/// The markers of the objects every motion procedure uses.
struct Shared<'a> {
    handle: &'a Ident,
    control: &'a Ident,
    status: &'a Ident,
    request: Ident,
    display: Ident,
    actual: Ident,
}

impl Shared<'_> {
    /// The `impl` header of a procedure: a blocking handle whose link reads and writes the
    /// shared objects and writes `written` (and the extra bounds).
    fn header(&self, written: &Ident, extra: TokenStream) -> TokenStream {
        let (handle, control, status) = (self.handle, self.control, self.status);
        let (request, display, actual) = (&self.request, &self.display, &self.actual);
        quote! {
            #[cfg(feature = "std")]
            impl<L: ::drivebus::Link> #handle<L>
            where
                params::#control: ::drivebus::Readable<L::Protocol> + ::drivebus::Writable<L::Protocol>,
                params::#status: ::drivebus::Readable<L::Protocol>,
                params::#request: ::drivebus::Writable<L::Protocol>,
                params::#display: ::drivebus::Readable<L::Protocol>,
                params::#written: ::drivebus::Writable<L::Protocol>,
                params::#actual: ::drivebus::Readable<L::Protocol>,
                #extra
        }
    }
}

/// The motion impls and methods of `handle`; empty where the description lacks the objects.
pub fn emit(device: &Device, handle: &Ident, control: &Ident, status: &Ident) -> TokenStream {
    let position = position(device, handle, control, status);
    let targets = targets::emit(device, handle, control, status);
    quote! {
        #position
        #targets
    }
}

/// The markers of the modes of operation (6060h) and their display (6061h).
fn modes(device: &Device) -> Option<(Ident, Ident)> {
    let request = object(device, 0x6060, 0, DataType::Signed(1))?;
    let display = object(device, 0x6061, 0, DataType::Signed(1))?;
    Some((marker(request), marker(display)))
}

/// `move_to` and `home`.
fn position(device: &Device, handle: &Ident, control: &Ident, status: &Ident) -> TokenStream {
    if !lists_mode(device, PROFILE_POSITION) {
        return TokenStream::new();
    }
    let Some(target) = object(device, 0x607A, 0, DataType::Signed(4)) else {
        return TokenStream::new();
    };
    let actual = object(device, 0x6064, 0, DataType::Signed(4))
        .or_else(|| object(device, 0x6063, 0, DataType::Signed(4)));
    let Some(actual) = actual else {
        return TokenStream::new();
    };
    let (target, actual) = (marker(target), marker(actual));
    let Some((request, display)) = modes(device) else {
        return TokenStream::new();
    };
    let (read_limits, limit_bounds) = limits(device);
    let shared = Shared {
        handle,
        control,
        status,
        request,
        display,
        actual,
    };
    let header = shared.header(&target, limit_bounds);
    let homing = homing(device, &shared);
    let actual = &shared.actual;
    quote! {
        impl<L> ::drivebus::control::ProfilePositionObjects for #handle<L> {
            type TargetPosition = params::#target;
            type PositionActual = params::#actual;
        }

        #header
        {
            /// Profile position move: switches to profile position mode, writes the target,
            /// runs the set-point handshake (controlword bit 4, statusword bit 12) and waits for
            /// target reached (bit 10) until `deadline`; returns the actual position. Refused
            /// before anything is sent when the drive is not operation enabled or the target
            /// lies outside the software position limits; a following error or time out halts
            /// the axis and is returned. Speeds and accelerations are the drive's (set them
            /// through their accessors).
            pub fn move_to(&mut self, request: ::drivebus::control::position::Move, deadline: ::drivebus::control::driver::Instant) -> Result<i32, ::drivebus::control::motion_error::MotionError> {
                let limits = #read_limits;
                ::drivebus::control::motion_driver::move_to::<Self, L>(&mut self.device, request, limits, deadline)
            }
        }

        #homing
    }
}

fn homing(device: &Device, shared: &Shared<'_>) -> TokenStream {
    if !lists_mode(device, HOMING) {
        return TokenStream::new();
    }
    let Some(method) = object(device, 0x6098, 0, DataType::Signed(1)) else {
        return TokenStream::new();
    };
    let Some(methods) = method.enumeration.as_deref() else {
        return TokenStream::new();
    };
    let (method, methods) = (marker(method), ident(&names::camel(methods)));
    let header = shared.header(&method, TokenStream::new());
    let handle = shared.handle;
    quote! {
        impl<L> ::drivebus::control::HomingObjects for #handle<L> {
            type Method = types::#methods;
            type HomingMethod = params::#method;
        }

        #header
        {
            /// Homing: switches to homing mode, writes `method`, starts homing (controlword bit
            /// 4) and waits for homing attained (statusword bits 12 and 10) until `deadline`;
            /// returns the actual position. The speeds, acceleration and home offset are the
            /// drive's (set them through their accessors). Refused before anything is sent when
            /// the method is not one the description lists or the drive is not operation
            /// enabled; a homing error or time out halts the axis and is returned.
            pub fn home(&mut self, method: types::#methods, deadline: ::drivebus::control::driver::Instant) -> Result<i32, ::drivebus::control::motion_error::MotionError> {
                ::drivebus::control::motion_driver::home::<Self, L>(&mut self.device, method, deadline)
            }
        }
    }
}
