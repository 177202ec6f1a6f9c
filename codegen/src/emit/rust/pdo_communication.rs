//! The communication side of a generated PDO struct: its defaults as constants (valid or not,
//! transmission type, inhibit time, event timer), the COB-ID as a function of the node id where
//! the description gives it, and the configuration to apply over SDO.

use proc_macro2::{Literal, TokenStream};
use quote::quote;

use super::{doc_attrs, ident};
use crate::ir::{Device, Direction, Mapping, PdoDefaults};

/// `0x190` / `0x180 + node id` / `not given`, for the struct's doc table.
pub(super) fn cob_id_text(defaults: &PdoDefaults) -> String {
    match defaults.cob_id {
        Some(c) if c.plus_node_id => format!("0x{:X} + node id", c.value),
        Some(c) => format!("0x{:X} (fixed: it does not follow the node id)", c.value),
        None => "not given by the description: choose one (`config_with_cob_id`)".to_owned(),
    }
}

/// The doc table rows of the communication defaults.
pub(super) fn doc_rows(m: &Mapping, defaults: &PdoDefaults) -> String {
    let mut text = format!(
        "\n| Valid by default | {} |",
        if m.enabled {
            "yes"
        } else {
            "no (COB-ID bit 31 set)"
        }
    );
    for (what, value) in [
        ("Transmission type", m.transmission_type.map(u16::from)),
        ("Inhibit time (raw)", defaults.inhibit_time),
        ("Event timer (raw)", defaults.event_timer),
    ] {
        if let Some(v) = value {
            text += &format!("\n| {what} | {v} |");
        }
    }
    text
}

fn option_literal<T: Into<u64>>(value: Option<T>, suffix: &str) -> TokenStream {
    match value {
        Some(v) => {
            let lit: Literal = format!("{}{suffix}", v.into())
                .parse()
                .expect("an integer literal");
            quote! { Some(#lit) }
        }
        None => quote! { None },
    }
}

/// Whether the configuration writes communication sub-index `subindex`: not when the description
/// describes that object read-only (the SWD's RPDO inhibit times, lines 1341 and 1365).
fn writable(m: &Mapping, device: &Device, subindex: u8) -> bool {
    let Some((index, _)) = m.object_indices() else {
        return false;
    };
    !device
        .parameters
        .iter()
        .flat_map(|p| &p.canopen)
        .any(|a| a.index == index && a.subindex == subindex && !a.access.write)
}

/// The constants, `cob_id(node)` / `config(node)` when the COB-ID is given, and
/// `config_with_cob_id(cob_id)`.
pub(super) fn emit(
    m: &Mapping,
    defaults: &PdoDefaults,
    count: &Literal,
    device: &Device,
) -> TokenStream {
    let kind = ident(match m.direction {
        Direction::Tx => "Transmit",
        Direction::Rx => "Receive",
    });
    let number = Literal::u16_unsuffixed(defaults.number);
    let enabled = m.enabled;
    let transmission_type = option_literal(m.transmission_type, "u8");
    let inhibit_time = option_literal(defaults.inhibit_time, "u16");
    let event_timer = option_literal(defaults.event_timer, "u16");
    let [written_inhibit_time, written_event_timer] = [(3, "INHIBIT_TIME"), (5, "EVENT_TIMER")]
        .map(|(subindex, constant)| {
            let constant = ident(constant);
            if writable(m, device, subindex) {
                quote! { Self::#constant }
            } else {
                quote! { None }
            }
        });
    let by_node = defaults.cob_id.map(|c| {
        let value: Literal = format!("0x{:X}", c.value)
            .parse()
            .expect("a hexadecimal integer is a literal");
        let (body, text) = if c.plus_node_id {
            (
                quote! { #value + node.get() as u32 },
                format!("The COB-ID on node `node`: 0x{:X} + node id.", c.value),
            )
        } else {
            (
                quote! { let _ = node; #value },
                format!(
                    "The COB-ID: 0x{:X} on every node (it does not follow the node id).",
                    c.value
                ),
            )
        };
        let docs = doc_attrs(&text);
        quote! {
            #docs
            pub const fn cob_id(node: NodeId) -> u32 {
                #body
            }

            /// The configuration that maps and enables this PDO on `node`, to apply over SDO in
            /// pre-operational (`config(node).apply(bus, node)`: disable, map, enable, as CiA 301
            /// orders it).
            pub fn config(node: NodeId) -> pdo::PdoConfig<'static> {
                Self::config_with_cob_id(Self::cob_id(node))
            }
        }
    });
    quote! {
        /// Whether the drive has this PDO valid by default (COB-ID bit 31 clear).
        pub const ENABLED_BY_DEFAULT: bool = #enabled;
        /// Default transmission type (communication sub-index 2), if the description gives it.
        pub const TRANSMISSION_TYPE: Option<u8> = #transmission_type;
        /// Default inhibit time (communication sub-index 3, raw), if the description gives it.
        pub const INHIBIT_TIME: Option<u16> = #inhibit_time;
        /// Default event timer (communication sub-index 5, raw), if the description gives it.
        pub const EVENT_TIMER: Option<u16> = #event_timer;

        #by_node

        /// The configuration that maps and enables this PDO under `cob_id` (bit 31 is cleared
        /// by the plan's last step), to apply over SDO in pre-operational. It writes the
        /// transmission type, inhibit time and event timer the description gives, except an
        /// object the description makes read-only.
        pub fn config_with_cob_id(cob_id: u32) -> pdo::PdoConfig<'static> {
            let layout: &'static pdo::PdoLayout<#count> = &Self::LAYOUT;
            pdo::PdoConfig {
                kind: pdo::PdoKind::#kind,
                number: #number,
                cob_id,
                transmission_type: Self::TRANSMISSION_TYPE,
                inhibit_time: #written_inhibit_time,
                event_timer: #written_event_timer,
                entries: layout.entries(),
            }
        }
    }
}
