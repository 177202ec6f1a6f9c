//! Indexed accessors of members described over a run of sub-indices (`subindex = "1..=8"`): one
//! handle method `drive.<name>(subindex)` returning an accessor that dispatches to the marker of
//! that sub-index, and refuses a sub-index outside the run with `ValueError::OutOfRange` before
//! anything is sent. The per-sub-index markers stay in `params` (for PDOs and `read_many`); the
//! handle has no method per member.

use proc_macro2::{Ident, Literal, TokenStream};
use quote::quote;

use super::{concat, doc_attrs, ident};
use crate::emit::{doc, ident as names};
use crate::ir::{Device, IndexedParameter, Parameter};

/// Whether `p` is a member of a run, reached through its run's indexed accessor.
pub(super) fn is_member(p: &Parameter, device: &Device) -> bool {
    device
        .indexed
        .iter()
        .any(|run| run.members.contains(&p.name))
}

/// The `indexed` module with one accessor type per run, and the handle methods.
pub(super) fn emit(device: &Device, handle: &Ident) -> TokenStream {
    if device.indexed.is_empty() {
        return quote! {};
    }
    let types = concat(device.indexed.iter().map(|run| accessor_type(run, device)));
    let methods = device.indexed.iter().map(handle_method);
    quote! {
        /// Accessors of members described once over a run of sub-indices: `drive.<name>(n)`.
        pub mod indexed {
            #[allow(unused_imports)]
            use super::params;
            #types
        }

        impl<L: ::drivebus::Link> #handle<L> {
            #( #methods )*
        }
    }
}

fn handle_method(run: &IndexedParameter) -> TokenStream {
    let method = ident(&names::method(&run.name));
    let ty = ident(&names::camel(&run.name));
    let summary = summary(run);
    let docs = doc_attrs(&format!(
        "{summary}\n\nSub-indices {first}..={last} of object 0x{index:04X}; see [`indexed::{ty}`].",
        first = run.first,
        last = run.last,
        index = run.index,
    ));
    quote! {
        #docs
        #[inline]
        pub fn #method(&mut self, subindex: u8) -> indexed::#ty<'_, L> {
            indexed::#ty::new(&mut self.device, subindex)
        }
    }
}

fn summary(run: &IndexedParameter) -> String {
    doc::summary(run.doc.as_deref(), &run.name)
}

/// Readable and writable over some protocol, judged from the members' CANopen access (a run has
/// exactly one address, a CANopen one).
fn access(run: &IndexedParameter, device: &Device) -> (bool, bool) {
    let first = run.members.first().and_then(|m| device.parameter(m));
    let address = first.and_then(|p| p.canopen.first());
    let safety = first.is_some_and(Parameter::is_safety);
    address.map_or((false, false), |a| {
        (a.access.read, a.access.write && !safety)
    })
}

fn accessor_type(run: &IndexedParameter, device: &Device) -> TokenStream {
    let ty = ident(&names::camel(&run.name));
    let markers: Vec<Ident> = run
        .members
        .iter()
        .map(|m| ident(&names::camel(m)))
        .collect();
    let subs: Vec<Literal> = (run.first..=run.last).map(Literal::u8_unsuffixed).collect();
    let Some(first) = markers.first() else {
        return quote! {};
    };
    let name = run.name.as_str();
    let (lo, hi) = (
        Literal::u8_unsuffixed(run.first),
        Literal::u8_unsuffixed(run.last),
    );
    let docs = doc_attrs(&format!(
        "{}\n\nSub-indices {}..={} of object 0x{:04X}, one marker each (`params::{}` ...).",
        summary(run),
        run.first,
        run.last,
        run.index,
        names::camel(&run.members[0]),
    ));
    let (readable, writable) = access(run, device);
    let value = quote! { <params::#first as ::drivebus::Parameter>::Value };
    let raw = quote! { <params::#first as ::drivebus::Parameter>::Raw };
    let read = readable.then(|| {
        quote! {
            /// Reads the value at this sub-index in engineering units.
            pub fn read(self) -> Result<#value, ::drivebus::Error>
            where #( params::#markers: ::drivebus::Readable<L::Protocol>, )*
            {
                match self.subindex {
                    #( #subs => self.device.read::<params::#markers>(), )*
                    _ => Err(self.out_of_range()),
                }
            }

            /// Reads the raw value at this sub-index.
            pub fn read_raw(self) -> Result<#raw, ::drivebus::Error>
            where #( params::#markers: ::drivebus::Readable<L::Protocol>, )*
            {
                match self.subindex {
                    #( #subs => self.device.read_raw::<params::#markers>(), )*
                    _ => Err(self.out_of_range()),
                }
            }
        }
    });
    let write = writable.then(|| {
        quote! {
            /// Writes a value in engineering units at this sub-index.
            pub fn write(self, value: #value) -> Result<(), ::drivebus::Error>
            where #( params::#markers: ::drivebus::Writable<L::Protocol>, )*
            {
                match self.subindex {
                    #( #subs => self.device.write::<params::#markers>(value), )*
                    _ => Err(self.out_of_range()),
                }
            }

            /// Writes a raw value at this sub-index.
            pub fn write_raw(self, raw: #raw) -> Result<(), ::drivebus::Error>
            where #( params::#markers: ::drivebus::Writable<L::Protocol>, )*
            {
                match self.subindex {
                    #( #subs => self.device.write_raw::<params::#markers>(raw), )*
                    _ => Err(self.out_of_range()),
                }
            }
        }
    });
    quote! {
        #docs
        #[must_use = "an accessor does nothing until read or written"]
        pub struct #ty<'d, L> {
            device: &'d mut ::drivebus::Device<L>,
            subindex: u8,
        }

        impl<'d, L> #ty<'d, L> {
            /// First sub-index of the run.
            pub const FIRST: u8 = #lo;
            /// Last sub-index of the run.
            pub const LAST: u8 = #hi;

            pub(super) fn new(device: &'d mut ::drivebus::Device<L>, subindex: u8) -> Self {
                Self { device, subindex }
            }

            /// The sub-index this accessor reaches.
            pub fn subindex(&self) -> u8 {
                self.subindex
            }
        }

        impl<L: ::drivebus::Link> #ty<'_, L> {

            /// The error for a sub-index outside the run; nothing is sent.
            #[allow(dead_code)]
            fn out_of_range(&self) -> ::drivebus::Error {
                ::drivebus::Error::Value(::drivebus::ValueError::OutOfRange {
                    parameter: #name,
                    raw: ::drivebus::interpret::RawValue::Int(i128::from(self.subindex)),
                    min: ::drivebus::interpret::RawValue::Int(#lo),
                    max: ::drivebus::interpret::RawValue::Int(#hi),
                })
            }

            #read
            #write
        }
    }
}
