//! The identity check on connect (`[identity]`): the handle's `verify_identity` reads every
//! identity parameter the link's protocol reaches (the firmware / configuration parameter, and
//! over CANopen the vendor-ID, product code and revision at 1018h) and, on a value the
//! description does not cover, refuses every write (`WriteRefusal::IdentityMismatch`, or
//! `IdentityOutOfRange` for a revision range) and returns
//! the refusal naming the parameter, expected and found values. `trust_unverified` is the
//! explicit opt-in to write anyway. A fresh handle is open: existing code keeps writing; calling
//! `verify_identity` first is the documented way to connect.
//!
//! Which checks a protocol runs is known per protocol, so they live in the `IdentityChecks`
//! trait, implemented for each protocol marker that reaches at least one identity parameter.

use proc_macro2::TokenStream;
use quote::quote;

use super::read_protocols::read_protocols;

use super::{doc_attrs, ident};
use crate::emit::ident as names;
use crate::ir::{Covered, Device, IdentityCheck};

pub fn emit(device: &Device) -> TokenStream {
    let checks: Vec<IdentityCheck> = device.identity_checks();
    if checks.is_empty() {
        return TokenStream::new();
    }
    let handle = ident(&names::camel(&device.device.handle));
    let protocols = read_protocols();
    let impls = protocols.iter().filter_map(|(protocol, readable)| {
        let reached: Vec<TokenStream> = checks
            .iter()
            .filter(|check| readable(check.parameter))
            .map(one_check)
            .collect();
        (!reached.is_empty()).then(|| {
            quote! {
                impl IdentityChecks for #protocol {
                    fn mismatch<L: ::drivebus::Link<Protocol = Self>>(
                        device: &mut ::drivebus::Device<L>,
                    ) -> Result<Option<(&'static str, ::drivebus::WriteRefusal)>, ::drivebus::Error> {
                        #( #reached )*
                        Ok(None)
                    }
                }
            }
        })
    });
    let described: Vec<String> = checks
        .iter()
        .map(|check| format!("`{}` in `{}`", check.parameter.name, check.covered))
        .collect();
    let verify_doc = doc_attrs(&format!(
        "Reads the identity parameters this link reaches ({}) and checks them against the values \
         the description covers. On a mismatch every later write is refused before sending, and \
         the refusal (naming the parameter, expected and found values) comes back as \
         `Error::WritesRefused`; reads go on. Call it right after connecting; \
         `trust_unverified` is the explicit opt-in to write anyway.",
        described.join(", ")
    ));
    let legacy = identity_values(&checks, device);
    quote! {
        #legacy

        /// The identity checks a protocol can run: the `[identity]` parameters it reads.
        pub trait IdentityChecks: ::drivebus::Protocol {
            /// Reads each identity parameter in turn; the first one holding a value the
            /// description does not cover, with the refusal naming it.
            fn mismatch<L: ::drivebus::Link<Protocol = Self>>(
                device: &mut ::drivebus::Device<L>,
            ) -> Result<Option<(&'static str, ::drivebus::WriteRefusal)>, ::drivebus::Error>;
        }

        #( #impls )*

        impl<L: ::drivebus::Link> #handle<L>
        where
            L::Protocol: IdentityChecks,
        {
            #verify_doc
            pub fn verify_identity(&mut self) -> Result<(), ::drivebus::Error> {
                let Some((parameter, reason)) =
                    <L::Protocol as IdentityChecks>::mismatch(&mut self.device)?
                else {
                    return Ok(());
                };
                self.device.refuse_writes(reason);
                Err(::drivebus::Error::WritesRefused { parameter, reason })
            }
        }

        impl<L: ::drivebus::Link> #handle<L> {
            /// Writes to this drive although `verify_identity` found (or was not asked to check)
            /// a drive, firmware or configuration the description does not cover: the explicit,
            /// visible opt-in. Lifts every refusal of writes.
            pub fn trust_unverified(&mut self) {
                self.device.lift_write_refusal();
            }
        }
    }
}

/// Reads one identity parameter and returns the refusal when its value is not covered.
fn one_check(check: &IdentityCheck) -> TokenStream {
    let marker = ident(&names::camel(&check.parameter.name));
    let name = &check.parameter.name;
    let (prelude, uncovered, reason) = match &check.covered {
        Covered::Values(values) => {
            let values = values.iter().map(|v| super::unsuffixed(i128::from(*v)));
            (
                quote! { const EXPECTED: &[::core::primitive::i128] = &[#( #values ),*]; },
                quote! { !EXPECTED.contains(&found) },
                quote! {
                    ::drivebus::WriteRefusal::IdentityMismatch {
                        parameter: #name,
                        expected: EXPECTED,
                        found,
                    }
                },
            )
        }
        Covered::Range { min, max } => {
            let (min, max) = (i128::from(*min), i128::from(*max));
            (
                TokenStream::new(),
                quote! { !(#min..=#max).contains(&found) },
                quote! {
                    ::drivebus::WriteRefusal::IdentityOutOfRange {
                        parameter: #name,
                        min: #min,
                        max: #max,
                        found,
                    }
                },
            )
        }
    };
    quote! {
        {
            #prelude
            let found = ::core::primitive::i128::from(device.read_raw::<params::#marker>()?);
            if #uncovered {
                let reason = #reason;
                return Ok(Some((#name, reason)));
            }
        }
    }
}

/// `IDENTITY_VALUES`: the values of the firmware / configuration parameter, when there is one.
fn identity_values(checks: &[IdentityCheck], device: &Device) -> TokenStream {
    let named = device
        .identity
        .as_ref()
        .and_then(|i| i.parameter.as_deref());
    let Some(Covered::Values(values)) = checks
        .iter()
        .find(|check| Some(check.parameter.name.as_str()) == named)
        .map(|check| &check.covered)
    else {
        return TokenStream::new();
    };
    let values = values.iter().map(|v| super::unsuffixed(i128::from(*v)));
    quote! {
        /// The values of the identity parameter this description covers.
        pub const IDENTITY_VALUES: &[::core::primitive::i128] = &[#( #values ),*];
    }
}
