//! Declared PDOs and SRDOs as typed structs: one field per carried parameter (its engineering
//! value, or its raw value when the scale is resolved at run time), and payload decode / encode
//! through the struct's `LAYOUT`. What each kind adds (the layout's origin, the communication
//! defaults, the docs) comes from [`super::pdo`] and [`super::srdo`].

use proc_macro2::{Ident, Literal, TokenStream};
use quote::quote;

use super::addresses::hex;
use super::parameter::value_type;
use super::{doc_attrs, ident, raw_type};
use crate::emit::doc;
use crate::ir::{pdo_bits, Device, Mapping, Parameter, Scale};
use crate::names;

/// `pub mod pdo { ... }` and `pub mod srdo { ... }`, each left out when the description
/// declares no mapping of its kind.
pub fn emit(device: &Device) -> TokenStream {
    let pdos: Vec<TokenStream> = device
        .pdos()
        .map(|(m, defaults)| super::pdo::emit(m, defaults, device))
        .collect();
    let srdos: Vec<TokenStream> = device
        .srdos()
        .map(|(m, defaults)| super::srdo::emit(m, defaults, device))
        .collect();
    let pdo = (!pdos.is_empty()).then(|| {
        quote! {
            /// The PDO mappings the description declares, as typed payloads.
            pub mod pdo {
                use ::drivebus::canopen::{pdo, NodeId};
                #( #pdos )*
            }
        }
    });
    let srdo = (!srdos.is_empty()).then(|| {
        quote! {
            /// The SRDOs (CANopen Safety, EN 50325-5) the description declares, as typed safety
            /// payloads. Needs `drivebus`'s `srdo` feature.
            pub mod srdo {
                use ::drivebus::canopen::{pdo, srdo, NodeId};
                #( #srdos )*
            }
        }
    });
    quote! { #pdo #srdo }
}

/// One carried parameter as the struct sees it.
pub(super) struct Field<'a> {
    pub(super) parameter: &'a Parameter,
    /// Whether the field holds the raw value (run-time scale) instead of the engineering one.
    raw: bool,
}

impl<'a> Field<'a> {
    pub(super) fn of(parameter: &'a Parameter) -> Self {
        Field {
            parameter,
            raw: matches!(parameter.scale, Some(Scale::Runtime { .. })),
        }
    }

    fn name(&self) -> Ident {
        ident(&names::method(&self.parameter.name))
    }

    fn marker(&self) -> TokenStream {
        let marker = ident(&names::camel(&self.parameter.name));
        quote! { super::params::#marker }
    }

    fn ty(&self) -> TokenStream {
        if self.raw {
            raw_type(self.parameter.data_type)
        } else {
            value_type(self.parameter, &quote! { super::types })
        }
    }
}

/// The parameters a mapping's entries name, in mapping-object order.
pub(super) fn parameters<'a>(m: &Mapping, device: &'a Device) -> Vec<&'a Parameter> {
    m.entries
        .iter()
        .filter_map(|e| device.parameter(e))
        .collect()
}

/// What a kind puts around the shared struct.
pub(super) struct KindParts {
    /// The struct's documentation.
    pub(super) doc: String,
    /// Items after the struct (a compile-time check).
    pub(super) after_struct: TokenStream,
    /// The first items of the `impl`: `LAYOUT` and what the kind configures.
    pub(super) constants: TokenStream,
    /// Documentation of `decode`.
    pub(super) decode_doc: &'static str,
    /// Documentation of `encode`.
    pub(super) encode_doc: &'static str,
}

/// The struct of mapping `m` carrying `fields`, with `decode` / `encode` through `Self::LAYOUT`.
pub(super) fn mapping(m: &Mapping, fields: &[Field], kind: KindParts) -> TokenStream {
    let name = ident(&names::camel(&m.name));
    let docs = doc_attrs(&kind.doc);
    let declarations = fields.iter().map(|f| {
        let (field, ty) = (f.name(), f.ty());
        let docs = doc_attrs(&field_doc(f));
        quote! { #docs pub #field: #ty, }
    });
    let count = Literal::usize_unsuffixed(fields.len());
    let (decode, encode) = (decode(fields, &count), encode(fields, &count));
    let (after_struct, constants) = (kind.after_struct, kind.constants);
    let (decode_doc, encode_doc) = (doc_attrs(kind.decode_doc), doc_attrs(kind.encode_doc));
    quote! {
        #docs
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub struct #name {
            #( #declarations )*
        }

        #after_struct

        impl #name {
            #constants

            #decode_doc
            pub fn decode(payload: &[u8]) -> Result<Self, ::drivebus::ValueError> {
                Ok(Self { #( #decode )* })
            }

            #encode_doc
            pub fn encode(&self) -> Result<::drivebus::canopen::pdo::Payload, ::drivebus::ValueError> {
                let mut payload = [0u8; 8];
                #( #encode )*
                Ok(::drivebus::canopen::pdo::Payload::new(payload, Self::LAYOUT.len()))
            }
        }
    }
}

/// `MappedObject::new(index, subindex, bits)` of a carried parameter.
pub(super) fn mapped_object(p: &Parameter) -> TokenStream {
    let object = p.pdo_object().expect("validated: mapped objects exist");
    let index = hex(object.index);
    let subindex = Literal::u8_unsuffixed(object.subindex);
    let bits = Literal::u32_unsuffixed(pdo_bits(p.data_type));
    quote! { ::drivebus::canopen::pdo::MappedObject::new(#index, #subindex, #bits) }
}

/// Bytes the fields take, packed from bit 0.
pub(super) fn payload_bytes(fields: &[Field]) -> u32 {
    let bits: u32 = fields.iter().map(|f| pdo_bits(f.parameter.data_type)).sum();
    bits.div_ceil(8)
}

/// One piece of code per field, from the field, its name, marker and position.
fn per_field(
    fields: &[Field],
    each: impl Fn(&Field, Ident, TokenStream, Literal) -> TokenStream,
) -> Vec<TokenStream> {
    fields
        .iter()
        .enumerate()
        .map(|(i, f)| each(f, f.name(), f.marker(), Literal::usize_unsuffixed(i)))
        .collect()
}

fn decode(fields: &[Field], count: &Literal) -> Vec<TokenStream> {
    per_field(fields, |f, field, marker, i| {
        if f.raw {
            quote! { #field: Self::LAYOUT.get(payload, #i)?, }
        } else {
            quote! { #field: ::drivebus::canopen::pdo::decode_entry::<#marker, #count>(&Self::LAYOUT, payload, #i)?, }
        }
    })
}

fn encode(fields: &[Field], count: &Literal) -> Vec<TokenStream> {
    per_field(fields, |f, field, marker, i| {
        if f.raw {
            quote! { Self::LAYOUT.set(&mut payload, #i, self.#field)?; }
        } else {
            quote! { ::drivebus::canopen::pdo::encode_entry::<#marker, #count>(&Self::LAYOUT, &mut payload, #i, self.#field)?; }
        }
    })
}

fn field_doc(f: &Field) -> String {
    let p = f.parameter;
    let object = p.pdo_object().expect("validated: mapped objects exist");
    let summary = doc::summary(p.doc.as_deref(), &p.name);
    let raw = if f.raw {
        " Raw: its scale is resolved at run time."
    } else {
        ""
    };
    format!(
        "{summary}{raw}\n\n`0x{:04X}:{:02X}`, {} bits; see [`{}`](super::params::{}).",
        object.index,
        object.subindex,
        pdo_bits(p.data_type),
        names::camel(&p.name),
        names::camel(&p.name),
    )
}

/// The `| Source | ... |` row of a struct's doc table, when the mapping cites one.
pub(super) fn source_row(m: &Mapping, device: &Device) -> String {
    m.source
        .as_ref()
        .map(|c| {
            let cited = super::parameter_doc::citation(c, device);
            format!("\n| Source | {cited} |")
        })
        .unwrap_or_default()
}
