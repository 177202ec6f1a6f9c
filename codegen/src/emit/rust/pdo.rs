//! Declared PDO mappings as typed structs: one field per mapped parameter (its engineering value,
//! or its raw value when the scale is resolved at run time), the layout as a constant (so the
//! 8-byte limit is checked again by the compiler), payload decode / encode, the COB-ID as a
//! function of the node id, and the configuration to apply over SDO.

use proc_macro2::{Ident, Literal, TokenStream};
use quote::quote;

use super::addresses::hex;
use super::parameter::value_type;
use super::{doc_attrs, ident, raw_type};
use crate::emit::{doc, ident as names};
use crate::ir::{pdo_bits, Device, Parameter, PdoDirection, PdoMapping, Scale};

/// `pub mod pdo { ... }`, or nothing when the description declares no PDO.
pub fn emit(device: &Device) -> TokenStream {
    if device.pdos.is_empty() {
        return quote! {};
    }
    let mappings = device.pdos.iter().map(|m| mapping(m, device));
    quote! {
        /// The PDO mappings the description declares, as typed payloads.
        pub mod pdo {
            #( #mappings )*
        }
    }
}

/// One mapped parameter as the struct sees it (SRDO structs use it too).
pub(super) struct Field<'a> {
    pub(super) parameter: &'a Parameter,
    /// Whether the field holds the raw value (run-time scale) instead of the engineering one.
    pub(super) raw: bool,
}

impl Field<'_> {
    pub(super) fn name(&self) -> Ident {
        ident(&names::method(&self.parameter.name))
    }

    fn marker(&self) -> TokenStream {
        let marker = ident(&names::camel(&self.parameter.name));
        quote! { super::params::#marker }
    }

    pub(super) fn ty(&self) -> TokenStream {
        if self.raw {
            raw_type(self.parameter.data_type)
        } else {
            value_type(self.parameter, &quote! { super::types })
        }
    }
}

fn mapping(m: &PdoMapping, device: &Device) -> TokenStream {
    let fields: Vec<Field> = m
        .entries
        .iter()
        .filter_map(|e| device.parameter(e))
        .map(|parameter| Field {
            parameter,
            raw: matches!(parameter.scale, Some(Scale::Runtime { .. })),
        })
        .collect();
    let name = ident(&names::camel(&m.name));
    let docs = doc_attrs(&struct_doc(m, &fields, device));
    let declarations = fields.iter().map(|f| {
        let (field, ty) = (f.name(), f.ty());
        let docs = doc_attrs(&field_doc(f));
        quote! { #docs pub #field: #ty, }
    });
    let layout = layout(&fields);
    let count = Literal::usize_unsuffixed(fields.len());
    let (decode, encode) = (decode(&fields, &count), encode(&fields, &count));
    let config = super::pdo_communication::emit(m, &count, device);
    quote! {
        #docs
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub struct #name {
            #( #declarations )*
        }

        impl #name {
            /// The mapping, packed from bit 0 in this order. A constant: a mapping over 8 bytes
            /// does not compile.
            pub const LAYOUT: ::drivebus::canopen::pdo::PdoLayout<#count> = #layout;

            #config

            /// Decodes a received payload; a payload shorter than the mapping is an error.
            pub fn decode(payload: &[u8]) -> Result<Self, ::drivebus::ValueError> {
                Ok(Self { #( #decode )* })
            }

            /// Encodes the values, range-checked, into a payload of the mapping's length.
            pub fn encode(&self) -> Result<::drivebus::canopen::pdo::Payload, ::drivebus::ValueError> {
                let mut payload = [0u8; 8];
                #( #encode )*
                Ok(::drivebus::canopen::pdo::Payload::new(payload, Self::LAYOUT.len()))
            }
        }
    }
}

fn layout(fields: &[Field]) -> TokenStream {
    let entries = fields.iter().map(|f| {
        let object = f
            .parameter
            .pdo_object()
            .expect("validated: mapped objects exist");
        let index = hex(object.index);
        let subindex = Literal::u8_unsuffixed(object.subindex);
        let bits = Literal::u32_unsuffixed(pdo_bits(f.parameter.data_type));
        quote! { ::drivebus::canopen::pdo::MappedObject::new(#index, #subindex, #bits) }
    });
    quote! { ::drivebus::canopen::pdo::PdoLayout::new([#( #entries ),*]) }
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

pub(super) fn decode(fields: &[Field], count: &Literal) -> Vec<TokenStream> {
    per_field(fields, |f, field, marker, i| {
        if f.raw {
            quote! { #field: Self::LAYOUT.get(payload, #i)?, }
        } else {
            quote! { #field: ::drivebus::canopen::pdo::decode_entry::<#marker, #count>(&Self::LAYOUT, payload, #i)?, }
        }
    })
}

pub(super) fn encode(fields: &[Field], count: &Literal) -> Vec<TokenStream> {
    per_field(fields, |f, field, marker, i| {
        if f.raw {
            quote! { Self::LAYOUT.set(&mut payload, #i, self.#field)?; }
        } else {
            quote! { ::drivebus::canopen::pdo::encode_entry::<#marker, #count>(&Self::LAYOUT, &mut payload, #i, self.#field)?; }
        }
    })
}

fn struct_doc(m: &PdoMapping, fields: &[Field], device: &Device) -> String {
    let (way, base) = match m.direction {
        PdoDirection::Tx => ("Transmit PDO", 0x1800),
        PdoDirection::Rx => ("Receive PDO", 0x1400),
    };
    let intro = doc::escape(m.doc.as_deref().unwrap_or(&m.name));
    let bits: u32 = fields.iter().map(|f| pdo_bits(f.parameter.data_type)).sum();
    let cob_id = super::pdo_communication::cob_id_text(m);
    let mut text = format!(
        "{intro}\n\n| | |\n|---|---|\n| PDO | {way} {}, communication object `0x{:04X}` |\n| COB-ID | {cob_id} |\n| Payload | {} bytes |",
        m.number,
        base + m.number - 1,
        bits.div_ceil(8)
    );
    text += &super::pdo_communication::doc_rows(m);
    if let Some(c) = &m.source {
        text += &format!(
            "\n| Source | {} |",
            super::parameter_doc::citation(c, device)
        );
    }
    text
}

pub(super) fn field_doc(f: &Field) -> String {
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
