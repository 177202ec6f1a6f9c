//! `quick_stop_by_option_code` on the handle, generated only where the description has the
//! quick stop option code (605Ah, i16): a quick stop seen through to the end the drive's own
//! code gives (`drivebus::control::driver::quick_stop_by_option_code`). Its async twin is
//! `async_handle!`'s `quick_stop_option` item ([`async_item`]).

use proc_macro2::{Ident, TokenStream};
use quote::quote;

use super::ident;
use crate::ir::{DataType, Device, Parameter};
use crate::names;

/// The quick stop option code (605Ah sub 0, i16), when the description has it.
fn option_code(device: &Device) -> Option<&Parameter> {
    device.parameters.iter().find(|p| {
        p.data_type == DataType::Signed(2)
            && p.canopen
                .iter()
                .any(|a| a.index == 0x605A && a.subindex == 0)
    })
}

/// The `QuickStopOptionObjects` impl and the method of `handle`, whose blocking control impl
/// is bounded by `bounds` (the controlword, statusword and safe torque off word); empty without
/// 605Ah.
pub fn emit(device: &Device, handle: &Ident, bounds: &TokenStream) -> TokenStream {
    let Some(code) = option_code(device) else {
        return TokenStream::new();
    };
    let code = ident(&names::camel(&code.name));
    quote! {
        impl<L> ::drivebus::control::QuickStopOptionObjects for #handle<L> {
            type QuickStopOptionCode = params::#code;
        }

        #[cfg(feature = "std")]
        impl<L: ::drivebus::Link> #handle<L>
        where
            #bounds
            params::#code: ::drivebus::Readable<L::Protocol>,
        {
            /// Quick stop seen through to the end the drive's quick stop option code (605Ah) gives:
            /// codes 0-4 wait, writing nothing, until the drive has braked and switched off
            /// (switch on disabled); codes 5-8 end in *quick stop active*. Disables from states
            /// other than operation enabled. The quick stop command goes out first (after the
            /// statusword and controlword reads it is made from); 605Ah is read only then, so a
            /// slow or failed read of the code never holds the stop back (a failed one takes
            /// either end).
            pub fn quick_stop_by_option_code(&mut self, deadline: ::drivebus::control::driver::Instant) -> Result<(), ::drivebus::control::driver::ControlError> {
                ::drivebus::control::driver::quick_stop_by_option_code::<Self, L>(&mut self.device, deadline)
            }
        }
    }
}

/// `, quick_stop_option` for `async_handle!` where the handle has the blocking method.
pub fn async_item(device: &Device) -> Option<TokenStream> {
    option_code(device).map(|_| quote! { , quick_stop_option })
}
