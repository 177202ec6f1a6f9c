//! Typed commands: a parameter with `command = { kind = "action", value }` is a command (several
//! may share one command register, Lenze smd #1). Its marker gets `TRIGGER`, the value it writes,
//! and its accessor the method `trigger()` of the generated `Trigger` trait, so
//! `drive.start().trigger()` writes exactly that value and nothing else.

use proc_macro2::TokenStream;
use quote::quote;

use super::{doc_attrs, enums::int_literal, ident, raw_type};
use crate::ir::{CommandKind, Device, Parameter};
use crate::names;

/// The action commands with a trigger value and a writable address.
fn triggered(device: &Device) -> impl Iterator<Item = (&Parameter, i64)> {
    device.parameters.iter().filter_map(|p| {
        let command = p.command.as_ref()?;
        let writable =
            p.modbus.iter().any(|a| a.access.write) || p.canopen.iter().any(|a| a.access.write);
        (command.kind == CommandKind::Action && writable && p.data_type.is_integer())
            .then_some((p, command.value?))
    })
}

pub fn emit(device: &Device) -> TokenStream {
    let impls: Vec<TokenStream> = triggered(device).map(|(p, v)| trigger(p, v)).collect();
    if impls.is_empty() {
        return TokenStream::new();
    }
    quote! {
        /// Commands of the drive: `drive.<command>().trigger()` writes the command's value.
        pub trait Trigger {
            /// Writes the command's trigger value (never retried).
            fn trigger(self) -> Result<(), ::drivebus::Error>;
        }
        #( #impls )*
    }
}

fn trigger(p: &Parameter, value: i64) -> TokenStream {
    let marker = ident(&names::camel(&p.name));
    let raw = raw_type(p.data_type);
    let literal = int_literal(i128::from(value), p.data_type);
    let const_doc = doc_attrs(&format!("The value that triggers `{}`.", p.name));
    quote! {
        impl params::#marker {
            #const_doc
            pub const TRIGGER: #raw = #literal;
        }

        impl<L: ::drivebus::Link> Trigger for ::drivebus::Accessor<'_, L, params::#marker>
        where
            params::#marker: ::drivebus::Writable<L::Protocol>,
        {
            fn trigger(self) -> Result<(), ::drivebus::Error> {
                self.write_raw(params::#marker::TRIGGER)
            }
        }
    }
}
