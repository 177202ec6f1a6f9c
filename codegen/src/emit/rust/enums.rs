//! Open enumerations: a newtype over the raw integer with one associated constant per documented
//! value. Unknown values survive a read; building one from a number goes through `TryFrom`.

use proc_macro2::{Literal, TokenStream};
use quote::quote;

use super::{doc_attrs, ident};
use crate::emit::{doc, ident as names};
use crate::ir::{DataType, Enum};

/// An integer literal of the given type, so negative and wide values print exactly.
pub fn int_literal(value: i128, ty: DataType) -> TokenStream {
    let lit = match ty.rust_type().as_str() {
        "u8" => Literal::u8_unsuffixed(value as u8),
        "u16" => Literal::u16_unsuffixed(value as u16),
        "u32" => Literal::u32_unsuffixed(value as u32),
        "u64" => Literal::u64_unsuffixed(value as u64),
        _ => Literal::i128_unsuffixed(value.abs()),
    };
    if value < 0 {
        quote! { -#lit }
    } else {
        quote! { #lit }
    }
}

pub fn emit(e: &Enum) -> TokenStream {
    let name = ident(&names::camel(&e.name));
    let raw = syn::parse_str::<syn::Type>(&e.data_type.rust_type()).expect("integer type");
    let intro = doc::escape(e.doc.as_deref().unwrap_or(&e.name));
    let docs = doc_attrs(&format!("{intro}\n\nOpen enumeration over `{}`: values the description does not list survive reads.", e.data_type.name()));
    let consts: Vec<_> = e
        .values
        .iter()
        .map(|v| ident(&names::constant(&v.name)))
        .collect();
    let values: Vec<_> = e
        .values
        .iter()
        .map(|v| int_literal(v.value as i128, e.data_type))
        .collect();
    let value_names = e.values.iter().map(|v| v.name.as_str());
    let const_docs = e.values.iter().map(|v| {
        let text = format!(
            "{} = `{}`",
            doc::escape(v.doc.as_deref().unwrap_or(&v.name)),
            v.value
        );
        doc_attrs(&text)
    });
    quote! {
        #docs
        #[derive(Clone, Copy, PartialEq, Eq, Hash)]
        pub struct #name(#raw);

        impl #name {
            #( #const_docs pub const #consts: Self = Self(#values); )*
            /// Every documented value.
            pub const VALUES: &'static [Self] = &[#( Self::#consts ),*];

            /// Wraps any raw value; only reads use this, users go through `TryFrom`.
            #[allow(dead_code)]
            pub(crate) const fn from_raw(raw: #raw) -> Self {
                Self(raw)
            }
            /// The raw value.
            pub const fn raw(self) -> #raw {
                self.0
            }
            /// The description's name for the value, `None` for an undocumented value.
            pub const fn name(self) -> Option<&'static str> {
                match self.0 {
                    #( #values => Some(#value_names), )*
                    _ => None,
                }
            }
            /// Whether the description documents this value.
            pub const fn is_known(self) -> bool {
                self.name().is_some()
            }
        }

        impl ::core::convert::TryFrom<#raw> for #name {
            type Error = ::drivebus::ValueError;
            fn try_from(raw: #raw) -> Result<Self, Self::Error> {
                let value = Self(raw);
                if value.is_known() {
                    Ok(value)
                } else {
                    Err(::drivebus::ValueError::NotAllowed { parameter: stringify!(#name), raw: raw as i128 })
                }
            }
        }

        impl ::core::fmt::Debug for #name {
            fn fmt(&self, f: &mut ::core::fmt::Formatter<'_>) -> ::core::fmt::Result {
                match self.name() {
                    Some(name) => f.write_str(name),
                    None => write!(f, "{}({})", stringify!(#name), self.0),
                }
            }
        }

        impl ::drivebus::parameter::OpenEnum for #name {
            type Raw = #raw;
            fn raw(self) -> #raw {
                self.0
            }
            fn name(self) -> Option<&'static str> {
                #name::name(self)
            }
        }
    }
}
