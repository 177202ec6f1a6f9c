//! The identity check on connect (`[identity]` with a `parameter`): the handle's
//! `verify_identity` reads the firmware / configuration parameter and, when its value is not one
//! the description covers, refuses every write (`WriteRefusal::IdentityMismatch`) and returns the
//! refusal naming expected and found values. `trust_unverified` is the explicit opt-in to write
//! anyway. A fresh handle is open: existing code keeps writing; calling `verify_identity` first
//! is the documented way to connect.

use proc_macro2::TokenStream;
use quote::quote;

use super::{doc_attrs, ident, raw_type};
use crate::emit::ident as names;
use crate::ir::Device;

pub fn emit(device: &Device) -> TokenStream {
    let Some(identity) = &device.identity else {
        return TokenStream::new();
    };
    let Some(parameter) = identity
        .parameter
        .as_deref()
        .and_then(|name| device.parameter(name))
    else {
        return TokenStream::new();
    };
    let handle = ident(&names::camel(&device.device.handle));
    let marker = ident(&names::camel(&parameter.name));
    let raw = raw_type(parameter.data_type);
    let name = &parameter.name;
    let values = identity.values.iter().map(|v| i128::from(*v));
    // In code spans: a bare `[242]` would be read as an intra-doc link.
    let covered: Vec<String> = identity.values.iter().map(|v| format!("`{v}`")).collect();
    let covered = covered.join(", ");
    let verify_doc = doc_attrs(&format!(
        "Reads `{name}` and checks it against the values the description covers ({}). On a \
         mismatch every later write is refused before sending, and the refusal (naming expected \
         and found values) comes back as `Error::WritesRefused`; reads go on. Call it right after \
         connecting; `trust_unverified` is the explicit opt-in to write anyway.",
        covered
    ));
    quote! {
        /// The values of the identity parameter this description covers.
        pub const IDENTITY_VALUES: &[::core::primitive::i128] = &[#( #values ),*];

        impl<L: ::drivebus::Link> #handle<L>
        where
            params::#marker: ::drivebus::Readable<L::Protocol, Raw = #raw>,
        {
            #verify_doc
            pub fn verify_identity(&mut self) -> Result<(), ::drivebus::Error> {
                let found = ::core::primitive::i128::from(self.device.read_raw::<params::#marker>()?);
                if IDENTITY_VALUES.contains(&found) {
                    return Ok(());
                }
                let reason = ::drivebus::WriteRefusal::IdentityMismatch {
                    parameter: #name,
                    expected: IDENTITY_VALUES,
                    found,
                };
                self.device.refuse_writes(reason);
                Err(::drivebus::Error::WritesRefused { parameter: #name, reason })
            }
        }

        impl<L: ::drivebus::Link> #handle<L> {
            /// Writes to this drive although `verify_identity` found (or was not asked to check)
            /// a firmware or configuration the description does not cover: the explicit,
            /// visible opt-in. Lifts every refusal of writes.
            pub fn trust_unverified(&mut self) {
                self.device.lift_write_refusal();
            }
        }
    }
}
