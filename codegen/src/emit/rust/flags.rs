//! Bit-field words as plain items: the newtype, one constant per named bit and an accessor per
//! multi-bit field, then one `drivebus::flags!` line for the bit-set API (`contains`, `|`, ...).

use proc_macro2::{Literal, TokenStream};
use quote::quote;

use super::{doc_attrs, ident, layout, raw_type};
use crate::emit::doc;
use crate::ir::{Device, Flags};
use crate::names;

pub fn emit(f: &Flags, device: &Device) -> TokenStream {
    let name = ident(&names::camel(&f.name));
    let raw = raw_type(f.data_type);
    let docs = doc_attrs(&format!(
        "{}\n\nBit-field word over `{}`; bits the description does not name are kept.",
        doc::escape(f.doc.as_deref().unwrap_or(&f.name)),
        f.data_type.name()
    ));
    let constants: Vec<_> = f
        .bits
        .iter()
        .map(|b| ident(&names::constant(&b.name)))
        .collect();
    let bits = f.bits.iter().zip(&constants).map(|(b, c)| {
        let d = doc_attrs(&format!(
            "Bit {}: {}",
            b.bit,
            doc::escape(b.doc.as_deref().unwrap_or(&b.name))
        ));
        let shift = Literal::u32_unsuffixed(b.bit);
        quote! { #d pub const #c: Self = Self(1 << #shift); }
    });
    let fields = f
        .fields
        .iter()
        .map(|field| field_accessor(f, field, device));
    let items = quote! { #( #bits )* #( #fields )* };
    let inherent = (!items.is_empty()).then(|| quote! { impl #name { #items } });
    let api = layout::list_call(
        "::drivebus::flags",
        quote! { #name: #raw = #( #constants ),* },
    );
    quote! {
        #docs
        #[derive(Clone, Copy, PartialEq, Eq, Hash)]
        pub struct #name(#raw);

        #inherent
        #api
    }
}

/// The `const fn` that reads a multi-bit field: its bits shifted down and masked, typed as the
/// field's enumeration when it has one.
fn field_accessor(f: &Flags, field: &crate::ir::BitField, device: &Device) -> TokenStream {
    let method = ident(&names::snake(&field.name));
    let (lsb, width) = (field.lsb, field.width);
    let mask = super::hex((1u128 << width) - 1);
    let d = doc_attrs(&format!(
        "Bits {lsb}..{}: {}",
        lsb + width,
        doc::escape(field.doc.as_deref().unwrap_or(&field.name))
    ));
    // No shift at bit 0 and no cast to the same type: the generated code stays lint-free.
    let bits = if lsb == 0 {
        quote! { self.0 & #mask }
    } else {
        let lsb = Literal::u32_unsuffixed(lsb);
        quote! { (self.0 >> #lsb) & #mask }
    };
    let raw = raw_type(f.data_type);
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
}
