//! The serial watchdog of `[watchdog]`: the handle's `watchdog_timeout()` reads the action
//! parameter and, unless its value disables the watchdog, the timeout (ms), so a keep-alive
//! knows how often to communicate; with drivebus's `async`, `watchdog_timeout_async()` on the
//! async handle.

use proc_macro2::TokenStream;
use quote::quote;

use super::{doc_attrs, ident};
use crate::ir::{Device, TimeoutEffect};
use crate::names;

pub fn emit(device: &Device) -> TokenStream {
    let Some(watchdog) = device.lock.as_ref().and_then(|l| l.watchdog.as_ref()) else {
        return TokenStream::new();
    };
    let handle = ident(&names::camel(&device.device.handle));
    let action = ident(&names::camel(&watchdog.action));
    let timeout = ident(&names::camel(&watchdog.timeout));
    let timeout_name = &watchdog.timeout;
    let disabled: Vec<i128> = watchdog
        .actions
        .iter()
        .filter(|a| a.does == TimeoutEffect::Disabled)
        .map(|a| i128::from(a.value))
        .collect();
    let listed: Vec<String> = disabled.iter().map(i128::to_string).collect();
    let docs = doc_attrs(&format!(
        "The serial watchdog's timeout: reads `{}` and, unless it is {} (the watchdog is off: \
         `None`), `{timeout_name}` in milliseconds. While an unlock is in force, the drive \
         expects a request within this time.",
        watchdog.action,
        if listed.is_empty() {
            "never".to_string()
        } else {
            listed.join(" or ")
        }
    ));
    let body = |awaited: TokenStream| {
        quote! {
            const DISABLED: &[::core::primitive::i128] = &[#( #disabled ),*];
            let action = ::core::primitive::i128::from(self.device.read_raw::<params::#action>() #awaited ?);
            if DISABLED.contains(&action) {
                return Ok(None);
            }
            let raw = ::core::primitive::i128::from(self.device.read_raw::<params::#timeout>() #awaited ?);
            let ms = ::core::primitive::u64::try_from(raw).map_err(|_| {
                ::drivebus::Error::Value(::drivebus::ValueError::Overflow { parameter: #timeout_name })
            })?;
            Ok(Some(::core::time::Duration::from_millis(ms)))
        }
    };
    let (blocking, awaited) = (body(quote! {}), body(quote! { .await }));
    // With drivebus's `async`: the same reads, awaited.
    let async_items = super::layout::block_call(
        "::drivebus::if_async",
        quote! {
            impl<L: ::drivebus::asynch::AsyncLink> #handle<::drivebus::asynch::Async<L>>
            where
                params::#action: ::drivebus::Readable<L::Protocol>,
                params::#timeout: ::drivebus::Readable<L::Protocol>,
            {
                /// `watchdog_timeout` awaited.
                pub async fn watchdog_timeout_async(&mut self) -> Result<Option<::core::time::Duration>, ::drivebus::Error> {
                    #awaited
                }
            }
        },
    );
    quote! {
        impl<L: ::drivebus::Link> #handle<L>
        where
            params::#action: ::drivebus::Readable<L::Protocol>,
            params::#timeout: ::drivebus::Readable<L::Protocol>,
        {
            #docs
            pub fn watchdog_timeout(&mut self) -> Result<Option<::core::time::Duration>, ::drivebus::Error> {
                #blocking
            }
        }
        #async_items
    }
}
