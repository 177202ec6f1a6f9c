//! Bit-field words: a `bitflags` type that keeps unnamed bits, plus an accessor per multi-bit field.

use proc_macro2::TokenStream;
use quote::quote;

use super::{doc_attrs, ident, raw_type};
use crate::emit::{doc, ident as names};
use crate::ir::{Device, Flags};

pub fn emit(f: &Flags, device: &Device) -> TokenStream {
    let name = ident(&names::camel(&f.name));
    let raw = raw_type(f.data_type);
    let docs = doc_attrs(&format!(
        "{}\n\nBit-field word over `{}`; bits the description does not name are kept.",
        doc::escape(f.doc.as_deref().unwrap_or(&f.name)),
        f.data_type.name()
    ));
    let bits = f.bits.iter().map(|b| {
        let c = ident(&names::constant(&b.name));
        let d = doc_attrs(&format!(
            "Bit {}: {}",
            b.bit,
            doc::escape(b.doc.as_deref().unwrap_or(&b.name))
        ));
        let shift = b.bit;
        quote! { #d const #c = 1 << #shift; }
    });
    let fields = f.fields.iter().map(|field| {
        let method = ident(&names::snake(&field.name));
        let (lsb, width) = (field.lsb, field.width);
        let mask = super::enums::int_literal((1i128 << width) - 1, f.data_type);
        let d = doc_attrs(&format!(
            "Bits {lsb}..{}: {}",
            lsb + width,
            doc::escape(field.doc.as_deref().unwrap_or(&field.name))
        ));
        // No shift at bit 0 and no cast to the same type: the generated code stays lint-free.
        let shifted = if lsb == 0 {
            quote! { self.bits() }
        } else {
            quote! { (self.bits() >> #lsb) }
        };
        let bits = quote! { #shifted & #mask };
        match field
            .enumeration
            .as_deref()
            .and_then(|e| device.enumeration(e))
        {
            Some(e) => {
                let ty = ident(&names::camel(&e.name));
                let e_raw = raw_type(e.data_type);
                let value = if e.data_type == f.data_type {
                    bits
                } else {
                    quote! { (#bits) as #e_raw }
                };
                quote! { #d pub const fn #method(&self) -> #ty { #ty::from_raw(#value) } }
            }
            None => quote! { #d pub const fn #method(&self) -> #raw { #bits } },
        }
    });
    quote! {
        ::drivebus::bitflags::bitflags! {
            #docs
            #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
            pub struct #name: #raw {
                #( #bits )*
                // Bits the description does not name still round-trip.
                const _ = !0;
            }
        }

        impl #name {
            #( #fields )*
        }
    }
}
