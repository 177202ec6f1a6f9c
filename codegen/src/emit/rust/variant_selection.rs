//! Variants the drive reports at run time (`[[variant]] selected_by`): `Variant::selected_by`
//! maps a raw value of the selecting parameter to a variant, and the handle's `detect_variant`
//! reads it and selects the variant, or reports the value no variant covers; over an async link
//! (drivebus's `async`, `drivebus::async_handle!`'s `variant`) `detect_variant_async` does the
//! same with the read awaited.

use proc_macro2::TokenStream;
use quote::quote;

use super::{doc_attrs, enums::int_literal, ident, raw_type};
use crate::ir::Device;
use crate::names;

pub fn emit(device: &Device) -> TokenStream {
    let Some((parameter, values)) = device.variant_selection() else {
        return TokenStream::new();
    };
    let handle = ident(&names::camel(&device.device.handle));
    let marker = ident(&names::camel(&parameter.name));
    let raw = raw_type(parameter.data_type);
    let arms = values.iter().map(|(i, value)| {
        let variant = ident(&names::camel(&device.variants[*i].name));
        let literal = int_literal(i128::from(*value), parameter.data_type);
        quote! { #literal => Some(Variant::#variant), }
    });
    let name = &parameter.name;
    let selected_doc = doc_attrs(&format!(
        "The variant the drive reports with this raw value of `{name}`, if any."
    ));
    let detect_doc = doc_attrs(&format!(
        "Reads `{name}` and selects the variant it names. A value no variant is selected by \
         comes back as [`VariantSelection::Unknown`]: until a later detection succeeds or \
         `set_variant` overrides it, a parameter whose address depends on the variant is not \
         read (`Error::VariantUnknown`) and every write but a stop is refused with \
         `Error::WritesRefused`; nothing is guessed and nothing is sent."
    ));
    quote! {
        /// What the drive reported about its variant.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum VariantSelection {
            /// A variant the description covers.
            Known(Variant),
            /// A value no variant is selected by: the description does not cover this drive's
            /// configuration.
            Unknown(#raw),
        }

        impl Variant {
            #selected_doc
            pub const fn selected_by(raw: #raw) -> Option<Variant> {
                match raw {
                    #( #arms )*
                    _ => None,
                }
            }
        }

        impl<L> #handle<L> {
            /// What `detect_variant` and `detect_variant_async` conclude from the raw value
            /// read: the variant it names, selected, or the refusal of writes.
            fn select_reported_variant(&mut self, raw: #raw) -> VariantSelection {
                match Variant::selected_by(raw) {
                    Some(variant) => {
                        self.set_variant(variant);
                        VariantSelection::Known(variant)
                    }
                    None => {
                        self.device.refuse_writes(::drivebus::WriteRefusal::UnknownVariant {
                            selector: #name,
                            value: ::core::primitive::i128::from(raw),
                        });
                        VariantSelection::Unknown(raw)
                    }
                }
            }
        }

        impl<L: ::drivebus::Link> #handle<L>
        where
            params::#marker: ::drivebus::Readable<L::Protocol, Raw = #raw>,
        {
            #detect_doc
            pub fn detect_variant(&mut self) -> Result<VariantSelection, ::drivebus::Error> {
                let raw = self.device.read_raw::<params::#marker>()?;
                Ok(self.select_reported_variant(raw))
            }
        }
    }
}
