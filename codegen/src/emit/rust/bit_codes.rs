//! The error codes a flags word's bits report (`codes = "<enum>"`, `code` per bit): a `CODES`
//! table and `codes()`, which turns the set bits into the enum's documented values — and so into
//! their `meaning()`, the manual's remedy.

use proc_macro2::TokenStream;
use quote::quote;

use super::ident;
use crate::ir::{Device, Flags};
use crate::names;

pub fn emit(f: &Flags, device: &Device) -> TokenStream {
    let Some(e) = f.codes.as_deref().and_then(|n| device.enumeration(n)) else {
        return quote! {};
    };
    let code_ty = ident(&names::camel(&e.name));
    let entries: Vec<TokenStream> = f
        .bits
        .iter()
        .filter_map(|b| {
            let value = e.values.iter().find(|v| Some(v.value) == b.code)?;
            let bit = ident(&names::constant(&b.name));
            let code = ident(&names::constant(&value.name));
            Some(quote! { (Self::#bit, #code_ty::#code) })
        })
        .collect();
    if entries.is_empty() {
        return quote! {};
    }
    let flags_ty = ident(&names::camel(&f.name));
    quote! {
        impl #flags_ty {
            /// Every bit that reports an error code, with that code.
            pub const CODES: &'static [(Self, #code_ty)] = &[ #( #entries ),* ];

            /// The codes of the set bits, in bit order; each code's `meaning()` is the manual's
            /// explanation and remedy.
            pub fn codes(&self) -> impl Iterator<Item = #code_ty> + '_ {
                Self::CODES
                    .iter()
                    .filter(move |(bit, _)| self.contains(*bit))
                    .map(|(_, code)| *code)
            }
        }
    }
}
