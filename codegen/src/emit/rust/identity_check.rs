//! The identity check on connect (`[identity]`): the handle's `verify_identity` reads every
//! identity parameter the link's protocol reaches (the firmware / configuration parameter, and
//! over CANopen the vendor-ID, product code and revision at 1018h) and, on a value the
//! description does not cover, refuses every write (`WriteRefusal::IdentityMismatch`, or
//! `IdentityOutOfRange` for a revision range) and returns
//! the refusal naming the parameter, expected and found values. `trust_unverified` is the
//! explicit opt-in to write anyway. A fresh handle is open: existing code keeps writing; calling
//! `verify_identity` first is the documented way to connect.
//!
//! Which checks a protocol runs is known per protocol: the handle implements
//! `drivebus::IdentityChecks` for each protocol that reaches at least one identity parameter,
//! with a table of `drivebus::IdentityCheck`s; `drivebus::Device::verify_identity` reads them,
//! and over an async link (drivebus's `async`, through `drivebus::async_handle!`'s `identity`)
//! the handle's `verify_identity_async` reads them with the async `Device::verify_identity`.

use proc_macro2::{Literal, TokenStream};
use quote::quote;

use super::read_protocols::read_protocols;

use super::{doc_attrs, ident};
use crate::ir::{Covered, Device, IdentityCheck};
use crate::names;

pub fn emit(device: &Device) -> TokenStream {
    let checks: Vec<IdentityCheck> = device.identity_checks();
    if checks.is_empty() {
        return TokenStream::new();
    }
    let handle = ident(&names::camel(&device.device.handle));
    let identity = identity_parameter(&checks, device);
    let protocols = read_protocols();
    let impls = protocols.iter().filter_map(|(protocol, readable)| {
        let reached: Vec<TokenStream> = checks
            .iter()
            .filter(|check| readable(check.parameter))
            .map(|check| one_check(check, identity))
            .collect();
        (!reached.is_empty()).then(|| {
            quote! {
                impl<L> ::drivebus::IdentityChecks<#protocol> for #handle<L> {
                    const IDENTITY_CHECKS: &'static [::drivebus::IdentityCheck<#protocol>] =
                        &[#( #reached ),*];
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
    let values = identity_values(&checks, identity);
    quote! {
        #values

        #( #impls )*

        impl<L: ::drivebus::Link> #handle<L>
        where
            Self: ::drivebus::IdentityChecks<L::Protocol>,
        {
            #verify_doc
            pub fn verify_identity(&mut self) -> Result<(), ::drivebus::Error> {
                self.device.verify_identity(
                    <Self as ::drivebus::IdentityChecks<L::Protocol>>::IDENTITY_CHECKS,
                )
            }
        }

        impl<L> #handle<L> {
            /// Writes to this drive although `verify_identity` found (or was not asked to check)
            /// a drive, firmware or configuration the description does not cover: the explicit,
            /// visible opt-in. Lifts every refusal of writes.
            pub fn trust_unverified(&mut self) {
                self.device.lift_write_refusal();
            }
        }
    }
}

/// One entry of a protocol's table: the parameter and the values covered, the identity
/// parameter's through `IDENTITY_VALUES`.
fn one_check(check: &IdentityCheck, identity: Option<&str>) -> TokenStream {
    let marker = ident(&names::camel(&check.parameter.name));
    let covered = match &check.covered {
        Covered::Values(_) if identity == Some(check.parameter.name.as_str()) => {
            quote! { ::drivebus::Covered::Values(IDENTITY_VALUES) }
        }
        Covered::Values(values) => {
            let values = values.iter().map(|v| super::unsuffixed(i128::from(*v)));
            quote! { ::drivebus::Covered::Values(&[#( #values ),*]) }
        }
        Covered::Range { min, max } => {
            let (min, max) = (
                Literal::i128_unsuffixed(i128::from(*min)),
                Literal::i128_unsuffixed(i128::from(*max)),
            );
            quote! { ::drivebus::Covered::Range { min: #min, max: #max } }
        }
    };
    quote! {
        ::drivebus::IdentityCheck {
            parameter: ::drivebus::RawInteger::of::<params::#marker>(),
            covered: #covered,
        }
    }
}

/// The firmware / configuration parameter of `[identity]`, when its check lists values.
fn identity_parameter<'a>(checks: &[IdentityCheck], device: &'a Device) -> Option<&'a str> {
    let named = device
        .identity
        .as_ref()
        .and_then(|i| i.parameter.as_deref())?;
    checks
        .iter()
        .any(|check| check.parameter.name == named && matches!(check.covered, Covered::Values(_)))
        .then_some(named)
}

/// `IDENTITY_VALUES`: the values of the firmware / configuration parameter, when there is one.
fn identity_values(checks: &[IdentityCheck], identity: Option<&str>) -> TokenStream {
    let Some(Covered::Values(values)) = checks
        .iter()
        .find(|check| Some(check.parameter.name.as_str()) == identity)
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
