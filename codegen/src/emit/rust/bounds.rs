//! Writes checked against bounds set by other parameters (`bounds = { min, max, magnitude }`): a
//! `BoundedWriteError` type, and per writable bounded parameter a handle method
//! `write_<name>(value)` that reads the bounds' current raw values, refuses a value beyond them
//! naming the bound, and only then writes.

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

/// One bound check: `raw` must not lie `beyond` the current value of `bound`.
fn check(p: &Parameter, bound: &str, beyond: TokenStream, at: &TokenStream) -> TokenStream {
    let marker = ident(&names::camel(bound));
    let refusal = outside(p, bound);
    quote! {
        let limit = #at.read_raw::<params::#marker>()?;
        if raw #beyond limit {
            #refusal
        }
    }
}

/// The magnitude check: `raw` must lie within ± the current value of `bound`, compared wide
/// because the bound may be of another integer type (an unsigned full scale).
fn check_magnitude(p: &Parameter, bound: &str, at: &TokenStream) -> TokenStream {
    let marker = ident(&names::camel(bound));
    let refusal = outside(p, bound);
    quote! {
        let limit = #at.read_raw::<params::#marker>()?;
        if (raw as i128).abs() > limit as i128 {
            #refusal
        }
    }
}

/// Refuses the write: `raw` lies beyond `limit`, the current value of `bound`.
fn outside(p: &Parameter, bound: &str) -> TokenStream {
    let name = &p.name;
    quote! {
        return Err(BoundedWriteError::OutsideBound {
            parameter: #name,
            bound: #bound,
            raw: raw as i128,
            limit: limit as i128,
        });
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
    let bounds = p.bounds.as_ref().expect("filtered on bounds");
    let marker = ident(&names::camel(&p.name));
    let method = ident(&format!("write_{}", names::snake(&p.name)));
    let marker_of = |b: &String| ident(&names::camel(b));
    let same_raw: Vec<_> = bounds
        .min
        .iter()
        .chain(&bounds.max)
        .map(marker_of)
        .collect();
    let magnitude_marker: Vec<_> = bounds.magnitude.iter().map(marker_of).collect();
    let min = bounds
        .min
        .as_deref()
        .map(|b| check(p, b, quote! { < }, &at));
    let max = bounds
        .max
        .as_deref()
        .map(|b| check(p, b, quote! { > }, &at));
    let magnitude = bounds
        .magnitude
        .as_deref()
        .map(|b| check_magnitude(p, b, &at));
    let described = bounds
        .names()
        .map(|b| format!("`{b}`"))
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
            #( params::#same_raw: ::drivebus::Readable<L::Protocol, Raw = <params::#marker as ::drivebus::Parameter>::Raw>, )*
            #( params::#magnitude_marker: ::drivebus::Readable<L::Protocol>, )*
        {
            #docs
            pub fn #method(
                &mut self,
                value: <params::#marker as ::drivebus::Parameter>::Value,
            ) -> Result<(), BoundedWriteError> {
                let scale = <params::#marker as ::drivebus::Writable<L::Protocol>>::write_scale(&mut #at)?;
                let raw = <params::#marker as ::drivebus::Parameter>::encode(value, scale)?;
                #min
                #max
                #magnitude
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
                OutsideBound {
                    /// The parameter being written.
                    parameter: &'static str,
                    /// The parameter whose current value it broke.
                    bound: &'static str,
                    /// The raw value asked for.
                    raw: i128,
                    /// The bound's current raw value.
                    limit: i128,
                },
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
                        Self::OutsideBound { parameter, bound, raw, limit } => write!(
                            f,
                            "{parameter}: raw value {raw} is beyond the current value {limit} of {bound}"
                        ),
                    }
                }
            }
        });
    }
}
