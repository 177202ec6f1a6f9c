//! The `Variant` enum: firmware / parameter-configuration variants, numbered for `VariantId`.

use proc_macro2::TokenStream;
use quote::quote;

use super::{doc_attrs, ident};
use crate::emit::doc;
use crate::ir::Device;
use crate::names;

pub fn emit(device: &Device) -> TokenStream {
    if device.variants.is_empty() {
        return quote! {};
    }
    let names: Vec<_> = device
        .variants
        .iter()
        .map(|v| ident(&names::camel(&v.name)))
        .collect();
    let entries = device
        .variants
        .iter()
        .zip(&names)
        .enumerate()
        .map(|(i, (v, name))| {
            let docs = doc_attrs(&doc::escape(v.doc.as_deref().unwrap_or(&v.name)));
            let default = (i == 0).then(|| quote! { #[default] });
            quote! { #docs #default #name }
        });
    let ids = (0..device.variants.len()).map(proc_macro2::Literal::usize_unsuffixed);
    quote! {
        /// Firmware or parameter-configuration variants of the drive; the first is the default.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
        pub enum Variant {
            #( #entries, )*
        }

        impl Variant {
            /// The runtime's number for this variant.
            pub const fn id(self) -> ::drivebus::VariantId {
                match self { #( Variant::#names => ::drivebus::VariantId(#ids), )* }
            }
        }
    }
}
