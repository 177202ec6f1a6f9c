//! What a PDO adds to its mapping struct: the layout as a constant (so the 8-byte limit is checked
//! again by the compiler), the communication defaults and configuration
//! ([`super::pdo_communication`]), and the doc table.

use proc_macro2::{Literal, TokenStream};
use quote::quote;

use super::mapping::{self, Field, KindParts};
use crate::emit::doc;
use crate::ir::{Device, Direction, Mapping, PdoDefaults};

/// The struct of PDO `m`: every entry is a field.
pub(super) fn emit(m: &Mapping, defaults: &PdoDefaults, device: &Device) -> TokenStream {
    let parameters = mapping::parameters(m, device);
    let fields: Vec<Field> = parameters.iter().map(|p| Field::of(p)).collect();
    let entries = parameters.iter().map(|p| mapping::mapped_object(p));
    let count = Literal::usize_unsuffixed(fields.len());
    let config = super::pdo_communication::emit(m, defaults, &count, device);
    let kind = KindParts {
        doc: struct_doc(m, defaults, &fields, device),
        after_struct: TokenStream::new(),
        constants: quote! {
            /// The mapping, packed from bit 0 in this order. A constant: a mapping over 8 bytes
            /// does not compile.
            pub const LAYOUT: pdo::PdoLayout<#count> =
                pdo::PdoLayout::new([#( #entries ),*]);

            #config
        },
        decode_doc: "Decodes a received payload; a payload shorter than the mapping is an error.",
        encode_doc: "Encodes the values, range-checked, into a payload of the mapping's length.",
    };
    mapping::mapping(m, &fields, kind)
}

fn struct_doc(m: &Mapping, defaults: &PdoDefaults, fields: &[Field], device: &Device) -> String {
    let (way, base) = match m.direction {
        Direction::Tx => ("Transmit PDO", 0x1800),
        Direction::Rx => ("Receive PDO", 0x1400),
    };
    let intro = doc::escape(m.doc.as_deref().unwrap_or(&m.name));
    let cob_id = super::pdo_communication::cob_id_text(defaults);
    let mut text = format!(
        "{intro}\n\n| | |\n|---|---|\n| PDO | {way} {}, communication object `0x{:04X}` |\n| COB-ID | {cob_id} |\n| Payload | {} bytes |",
        defaults.number,
        base + defaults.number - 1,
        mapping::payload_bytes(fields)
    );
    text += &super::pdo_communication::doc_rows(m, defaults);
    text += &mapping::source_row(m, device);
    text
}
