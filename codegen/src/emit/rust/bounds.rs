//! Writes checked against bounds set by other parameters (`bounds = { min, max, magnitude }`): a
//! `BoundedWriteError` type, and per writable bounded parameter a handle method
//! `write_<name>(value)` that reads the bounds' current raw values, refuses a value beyond them
//! naming the bound, and only then writes.

use drivebus_model::model::Described;
use drivebus_model::Bound;
use proc_macro2::TokenStream;
use quote::quote;

use super::{doc_attrs, ident};
use crate::emit::ident as names;
use crate::ir::{Device, Parameter};

pub fn emit(device: &Device) -> TokenStream {
    let bounded: Vec<&Parameter> = device
        .parameters
        .iter()
        .filter(|p| p.bounds.is_some() && writable(p))
        .collect();
    if bounded.is_empty() {
        return TokenStream::new();
    }
    let handle = ident(&names::camel(&device.device.handle));
    let methods = bounded.iter().map(|p| method(p, &handle, device));
    quote! {
        #ERROR_TYPE
        #( #methods )*
    }
}

fn writable(p: &Parameter) -> bool {
    p.modbus.iter().any(|a| a.access.write) || p.canopen.iter().any(|a| a.access.write)
}

/// One bound check (`drivebus::Bound::breached`): `raw` must not lie beyond the current value
/// of `bound`, else the write is refused naming it.
fn check(p: &Parameter, kind: Bound, bound: &str, at: &TokenStream) -> TokenStream {
    let marker = ident(&names::camel(bound));
    let kind = match kind {
        Bound::Min => quote! { Min },
        Bound::Max => quote! { Max },
        Bound::Magnitude => quote! { Magnitude },
    };
    let name = &p.name;
    quote! {
        let limit = #at.read_raw::<params::#marker>()? as i128;
        if ::drivebus::Bound::#kind.breached(raw as i128, limit) {
            return Err(BoundedWriteError::OutsideBound(::drivebus::OutsideBound {
                parameter: #name,
                bound: #bound,
                raw: raw as i128,
                limit,
            }));
        }
    }
}

/// Where the bounded write of `p` lives: the handle, or for a parameter that needs an unlock
/// the guard of the unlocks opening its scope. Returns the impl header's generics and self type,
/// its extra bounds and the path to the runtime device.
fn receiver(
    p: &Parameter,
    handle: &proc_macro2::Ident,
    device: &Device,
) -> (TokenStream, TokenStream, TokenStream) {
    match (device.lock.as_ref(), device.lock_scope_of(p)) {
        (Some(lock), Some(scope)) => {
            let opens = ident(&format!("Opens{}", names::camel(&scope.name)));
            let command = ident(&names::camel(&lock.command));
            (
                quote! { <'d, L: ::drivebus::Link, U: unlock::#opens> Unlocked<'d, L, U> },
                quote! { params::#command: ::drivebus::Writable<L::Protocol>, },
                quote! { self.drive.device },
            )
        }
        _ => (
            quote! { <L: ::drivebus::Link> #handle<L> },
            quote! {},
            quote! { self.device },
        ),
    }
}

fn method(p: &Parameter, handle: &proc_macro2::Ident, device: &Device) -> TokenStream {
    let (header, lock_bound, at) = receiver(p, handle, device);
    let marker = ident(&names::camel(&p.name));
    let method = ident(&format!("write_{}", names::snake(&p.name)));
    let bounding: Vec<(Bound, &str)> = p.bounded_by().each().collect();
    let readers = bounding.iter().map(|(_, b)| ident(&names::camel(b)));
    let checks = bounding.iter().map(|(kind, b)| check(p, *kind, b, &at));
    let described = bounding
        .iter()
        .map(|(_, b)| format!("`{b}`"))
        .collect::<Vec<_>>()
        .join(" and ");
    let docs = doc_attrs(&format!(
        "Writes `{}` after reading {described} and checking the value against their current \
         values; a value beyond one is refused with [`BoundedWriteError::OutsideBound`] naming \
         it, and nothing is written.",
        p.name
    ));
    quote! {
        impl #header
        where
            #lock_bound
            params::#marker: ::drivebus::Writable<L::Protocol>,
            #( params::#readers: ::drivebus::Readable<L::Protocol>, )*
        {
            #docs
            pub fn #method(
                &mut self,
                value: <params::#marker as ::drivebus::Parameter>::Value,
            ) -> Result<(), BoundedWriteError> {
                let scale = <params::#marker as ::drivebus::Writable<L::Protocol>>::write_scale(&mut #at)?;
                let raw = <params::#marker as ::drivebus::Parameter>::encode(value, scale)?;
                #( #checks )*
                #at.write_raw::<params::#marker>(raw)?;
                Ok(())
            }
        }
    }
}

/// The error type of bounded writes, emitted once.
const ERROR_TYPE: ErrorType = ErrorType;

struct ErrorType;

impl quote::ToTokens for ErrorType {
    fn to_tokens(&self, tokens: &mut TokenStream) {
        tokens.extend(quote! {
            /// Why a bounded write (`write_<parameter>`) was refused or failed.
            #[derive(Debug, Clone, PartialEq)]
            pub enum BoundedWriteError {
                /// Reading a bound, converting the value or the write itself failed.
                Drive(::drivebus::Error),
                /// The value lies beyond the current value of another parameter; nothing was
                /// written.
                OutsideBound(::drivebus::OutsideBound),
            }

            impl From<::drivebus::Error> for BoundedWriteError {
                fn from(error: ::drivebus::Error) -> Self {
                    Self::Drive(error)
                }
            }

            impl From<::drivebus::ValueError> for BoundedWriteError {
                fn from(error: ::drivebus::ValueError) -> Self {
                    Self::Drive(::drivebus::Error::Value(error))
                }
            }

            impl ::core::fmt::Display for BoundedWriteError {
                fn fmt(&self, f: &mut ::core::fmt::Formatter<'_>) -> ::core::fmt::Result {
                    match self {
                        Self::Drive(e) => write!(f, "{e}"),
                        Self::OutsideBound(refusal) => write!(f, "{refusal}"),
                    }
                }
            }
        });
    }
}
