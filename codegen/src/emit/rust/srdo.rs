//! What an SRDO adds to its mapping struct: one field per normal-data entry (the inverted
//! entries are the runtime's business), the mapping and the normal-data layout as constants
//! checked by the compiler, the COB-IDs as a function of the node-ID, the default configuration
//! (for the safety signature and the safety write), and a consumer / producer with the declared
//! times.

use proc_macro2::{Literal, TokenStream};
use quote::quote;

use super::ident;
use super::mapping::{self, Field, KindParts};
use crate::emit::doc;
use crate::ir::{Device, Direction, Mapping, SrdoCobId, SrdoDefaults};

/// The struct of SRDO `m`: the normal entries (every other one, from the first) are fields.
pub(super) fn emit(m: &Mapping, defaults: &SrdoDefaults, device: &Device) -> TokenStream {
    let parameters = mapping::parameters(m, device);
    let fields: Vec<Field> = parameters.iter().step_by(2).map(|p| Field::of(p)).collect();
    let name = ident(&crate::names::camel(&m.name));
    let entries = parameters.iter().map(|p| mapping::mapped_object(p));
    let total = Literal::usize_unsuffixed(parameters.len());
    let count = Literal::usize_unsuffixed(fields.len());
    let configuration = configuration(m, defaults);
    let kind = KindParts {
        doc: struct_doc(m, defaults, &fields, device),
        after_struct: quote! {
            const _: () = assert!(
                srdo::mapping::mapping_is_valid(&#name::MAPPING),
                "SRDO mapping does not pair or does not fit 8 bytes"
            );
        },
        constants: quote! {
            /// The mapping object's entries in sub-index order: normal, inverted, normal, ...
            pub const MAPPING: [pdo::MappedObject; #total] = [#( #entries ),*];

            /// The normal data, packed from bit 0 as a PDO is.
            pub const LAYOUT: pdo::PdoLayout<#count> =
                pdo::PdoLayout::new(
                    srdo::mapping::normal_entries::<#count>(&Self::MAPPING),
                );

            #configuration
        },
        decode_doc: "Decodes released normal data (from\n[`SrdoConsumer::handle`](::drivebus::canopen::srdo::SrdoConsumer::handle)).",
        encode_doc: "Encodes the values, range-checked, into the normal data (the producer sends it\nwith its inverted copy).",
    };
    mapping::mapping(m, &fields, kind)
}

fn cob_id_expr(id: &SrdoCobId) -> TokenStream {
    let base = Literal::u32_unsuffixed(id.base);
    if id.node_id_factor == 0 {
        return quote! { #base };
    }
    let factor = Literal::u32_unsuffixed(id.node_id_factor);
    quote! { #base + #factor * node.get() as u32 }
}

fn cob_id_text(id: &SrdoCobId) -> String {
    match id.node_id_factor {
        0 => format!("0x{:X}", id.base),
        1 => format!("0x{:X} + node-ID", id.base),
        f => format!("0x{:X} + {f} × node-ID", id.base),
    }
}

/// `NUMBER`, `communication(node)`, `config(node)`, `consumer(node)`, `producer(node)`.
fn configuration(m: &Mapping, s: &SrdoDefaults) -> TokenStream {
    let number = Literal::u8_unsuffixed(s.number);
    let direction = ident(match m.information_direction() {
        0 => "Invalid",
        1 => "Transmit",
        _ => "Receive",
    });
    let (sct, srvt) = (
        Literal::u16_unsuffixed(s.sct_ms),
        Literal::u16_unsuffixed(s.srvt_ms),
    );
    let transmission_type = Literal::u8_unsuffixed(m.transmission_type.unwrap_or(0xFE));
    let [normal, inverted] = s.cob_ids.each_ref().map(cob_id_expr);
    let uses_node = s.cob_ids.iter().any(|c| c.node_id_factor != 0);
    let ignore_node = (!uses_node).then(|| quote! { let _ = node; });
    quote! {
        /// The SRDO number (communication object 1300h + number, mapping 1380h + number,
        /// signature 13FFh sub number).
        pub const NUMBER: u8 = #number;

        /// The default communication parameters on `node`.
        pub fn communication(node: NodeId) -> srdo::SrdoCommunication {
            #ignore_node
            srdo::SrdoCommunication {
                direction: srdo::SrdoDirection::#direction,
                sct_ms: #sct,
                srvt_ms: #srvt,
                transmission_type: #transmission_type,
                cob_id_normal: #normal,
                cob_id_inverted: #inverted,
            }
        }

        /// The default configuration on `node`: what
        /// [`signature`](::drivebus::canopen::srdo::signature()) signs and the safety write writes.
        pub fn config(node: NodeId) -> srdo::SrdoConfig<'static> {
            srdo::SrdoConfig {
                number: Self::NUMBER,
                communication: Self::communication(node),
                mapping: &Self::MAPPING,
            }
        }

        /// A consumer of this SRDO from `node`, with the default times.
        pub fn consumer(node: NodeId) -> Result<srdo::SrdoConsumer, srdo::SrdoError> {
            let c = Self::communication(node);
            srdo::SrdoConsumer::new(
                c.cob_ids()?,
                c.timing()?,
                srdo::mapping::data_bits(&Self::MAPPING),
            )
        }

        /// A producer of this SRDO for `node`, sending every SCT.
        pub fn producer(node: NodeId) -> Result<srdo::SrdoProducer, srdo::SrdoError> {
            let c = Self::communication(node);
            srdo::SrdoProducer::new(
                c.cob_ids()?,
                c.timing()?.sct(),
                srdo::mapping::data_bits(&Self::MAPPING),
            )
        }
    }
}

fn struct_doc(m: &Mapping, s: &SrdoDefaults, fields: &[Field], device: &Device) -> String {
    let way = match m.direction {
        Direction::Tx => "transmitted by the drive",
        Direction::Rx => "received by the drive",
    };
    let state = if m.enabled {
        "valid"
    } else {
        "invalid (information direction 0)"
    };
    let intro = doc::escape(m.doc.as_deref().unwrap_or(&m.name));
    let mut text = format!(
        "{intro}\n\n| | |\n|---|---|\n| SRDO | {}, {way}, {state} by default; objects `0x{:04X}` / `0x{:04X}` |\n| COB-IDs | {} (normal), {} (inverted) |\n| SCT / SRVT | {} ms / {} ms |\n| Normal data | {} bytes, {} entries |",
        s.number,
        0x1300 + u16::from(s.number),
        0x1380 + u16::from(s.number),
        cob_id_text(&s.cob_ids[0]),
        cob_id_text(&s.cob_ids[1]),
        s.sct_ms,
        s.srvt_ms,
        mapping::payload_bytes(fields),
        fields.len(),
    );
    text += &mapping::source_row(m, device);
    if let Some(e) = &s.erratum {
        text += &format!("\n\nErratum: {}", doc::escape(e));
    }
    text
}
