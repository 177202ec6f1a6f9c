//! Motion procedures on the handle, generated only where the description has their objects
//! (issue 32): `move_to` when the modes enum lists profile position (1) and the drive has the
//! target position (607Ah) and a position actual value (6064h, else 6063h); `home` when the
//! modes list homing (6) and the homing method (6098h) is an enum of the methods the drive
//! lists; `run_at_velocity` when the modes list profile velocity (3) and the drive has the
//! target velocity (60FFh) and the velocity actual value (606Ch); `apply_torque` when the modes
//! list profile torque (4) and the drive has the target torque (6071h). A drive without them has
//! no such method: calling it does not compile. Each has an async twin on the async handle
//! (`move_to_async`, ...: drivebus's `async_motion_driver`), under drivebus's `async` and the
//! crate's `std`, with the same bounds.

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
/// with (each read followed by `awaited`: nothing, or `.await`), and the bounds that needs;
/// `None` when the drive has no limits.
fn limits(device: &Device, awaited: &TokenStream) -> (TokenStream, TokenStream) {
    let sub = |s| object(device, 0x607D, s, DataType::Signed(4)).map(marker);
    match (sub(1), sub(2)) {
        (Some(a), Some(b)) => (
            quote! {
                ::drivebus::control::position::SoftLimits::between(
                    self.device.read_raw::<params::#a>() #awaited ?,
                    self.device.read_raw::<params::#b>() #awaited ?,
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
    /// The `impl` headers of a procedure, blocking and awaited: the blocking handle, and the
    /// async one, whose links read and write the shared objects and write `written` (and the
    /// extra bounds).
    fn headers(&self, written: &Ident, extra: &TokenStream) -> (TokenStream, TokenStream) {
        let handle = self.handle;
        let bounds = self.bounds(written, extra);
        let blocking = quote! {
            #[cfg(feature = "std")]
            impl<L: ::drivebus::Link> #handle<L>
            where
                #bounds
        };
        let awaited = quote! {
            #[cfg(feature = "std")]
            impl<L: ::drivebus::asynch::AsyncLink> #handle<::drivebus::asynch::Async<L>>
            where
                #bounds
        };
        (blocking, awaited)
    }

    fn bounds(&self, written: &Ident, extra: &TokenStream) -> TokenStream {
        let (control, status) = (self.control, self.status);
        let (request, display, actual) = (&self.request, &self.display, &self.actual);
        quote! {
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

/// A procedure's items: the blocking ones, and their async twins (gated by the caller).
#[derive(Default)]
struct Items {
    blocking: TokenStream,
    awaited: TokenStream,
}

impl Items {
    fn extend(&mut self, other: Items) {
        self.blocking.extend(other.blocking);
        self.awaited.extend(other.awaited);
    }
}

/// The time parameters of an async procedure, after its own.
fn async_time() -> TokenStream {
    quote! { timer: &impl ::drivebus::asynch::Timer, limit: ::core::time::Duration }
}

/// The motion impls and methods of `handle`; empty where the description lacks the objects.
/// The async twins follow, with drivebus's `async` (through `drivebus::if_async!`).
pub fn emit(device: &Device, handle: &Ident, control: &Ident, status: &Ident) -> TokenStream {
    let mut items = position(device, handle, control, status);
    items.extend(targets::emit(device, handle, control, status));
    let Items { blocking, awaited } = items;
    if awaited.is_empty() {
        return blocking;
    }
    let awaited = super::layout::block_call("::drivebus::if_async", awaited);
    quote! {
        #blocking
        #awaited
    }
}

/// The markers of the modes of operation (6060h) and their display (6061h).
fn modes(device: &Device) -> Option<(Ident, Ident)> {
    let request = object(device, 0x6060, 0, DataType::Signed(1))?;
    let display = object(device, 0x6061, 0, DataType::Signed(1))?;
    Some((marker(request), marker(display)))
}

/// `move_to` and `home`.
fn position(device: &Device, handle: &Ident, control: &Ident, status: &Ident) -> Items {
    if !lists_mode(device, PROFILE_POSITION) {
        return Items::default();
    }
    let Some(target) = object(device, 0x607A, 0, DataType::Signed(4)) else {
        return Items::default();
    };
    let actual = object(device, 0x6064, 0, DataType::Signed(4))
        .or_else(|| object(device, 0x6063, 0, DataType::Signed(4)));
    let Some(actual) = actual else {
        return Items::default();
    };
    let (target, actual) = (marker(target), marker(actual));
    let Some((request, display)) = modes(device) else {
        return Items::default();
    };
    let (read_limits, limit_bounds) = limits(device, &TokenStream::new());
    let (read_limits_async, _) = limits(device, &quote! { .await });
    let shared = Shared {
        handle,
        control,
        status,
        request,
        display,
        actual,
    };
    let (header, async_header) = shared.headers(&target, &limit_bounds);
    let time = async_time();
    let actual = &shared.actual;
    let mut items = Items {
        blocking: quote! {
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
        },
        awaited: quote! {
            #async_header
            {
                /// `move_to` awaited: the same move, refusals and errors, polling on `timer` for
                /// at most `limit` (a time out halts the axis first).
                pub async fn move_to_async(&mut self, request: ::drivebus::control::position::Move, #time) -> Result<i32, ::drivebus::control::motion_error::MotionError> {
                    let limits = #read_limits_async;
                    ::drivebus::control::async_motion_driver::move_to::<Self, L>(&mut self.device, request, limits, timer, limit).await
                }
            }
        },
    };
    items.extend(homing(device, &shared));
    items
}

fn homing(device: &Device, shared: &Shared<'_>) -> Items {
    if !lists_mode(device, HOMING) {
        return Items::default();
    }
    let Some(method) = object(device, 0x6098, 0, DataType::Signed(1)) else {
        return Items::default();
    };
    let Some(methods) = method.enumeration.as_deref() else {
        return Items::default();
    };
    let (method, methods) = (marker(method), ident(&names::camel(methods)));
    let (header, async_header) = shared.headers(&method, &TokenStream::new());
    let time = async_time();
    let handle = shared.handle;
    Items {
        blocking: quote! {
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
        },
        awaited: quote! {
            #async_header
            {
                /// `home` awaited: the same homing run, refusals and errors, polling on `timer`
                /// for at most `limit` (a time out halts the axis first).
                pub async fn home_async(&mut self, method: types::#methods, #time) -> Result<i32, ::drivebus::control::motion_error::MotionError> {
                    ::drivebus::control::async_motion_driver::home::<Self, L>(&mut self.device, method, timer, limit).await
                }
            }
        },
    }
}
