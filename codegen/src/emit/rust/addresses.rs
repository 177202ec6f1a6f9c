//! Per-protocol address functions: which address a parameter is read or written at, per variant.

use proc_macro2::TokenStream;
use quote::quote;

use super::variants;
use crate::ir::{Access, Device, ModbusAddress, ObjectAddress, Parameter, Table, WordOrder};

/// Read or write.
#[derive(Clone, Copy)]
pub enum Direction {
    Read,
    Write,
}

impl Direction {
    fn allows(self, access: Access) -> bool {
        match self {
            Direction::Read => access.read,
            Direction::Write => access.write,
        }
    }
}

pub fn modbus_tokens(a: &ModbusAddress) -> TokenStream {
    let table = match a.table {
        Table::Input => quote! { Input },
        Table::Holding => quote! { Holding },
    };
    let order = match a.word_order {
        WordOrder::HighFirst => quote! { HighFirst },
        WordOrder::LowFirst => quote! { LowFirst },
    };
    let (address, words) = (a.address, a.words);
    quote! {
        ::drivebus::modbus::ModbusAddress {
            table: ::drivebus::modbus::Table::#table,
            address: #address,
            words: #words,
            word_order: ::drivebus::modbus::WordOrder::#order,
        }
    }
}

pub fn object_tokens(a: &ObjectAddress, bytes: u16) -> TokenStream {
    let (index, subindex) = (a.index, a.subindex);
    quote! { ::drivebus::canopen::ObjectAddress { index: #index, subindex: #subindex, bytes: #bytes } }
}

/// The body of `fn read_address(variant)` / `fn write_address(variant)`, or `None` if no address
/// allows the direction (then the capability trait is not implemented at all).
fn body<A>(
    p: &Parameter,
    device: &Device,
    addresses: &[A],
    direction: Direction,
    access: impl Fn(&A) -> Access,
    variant: impl Fn(&A) -> &Option<String>,
    tokens: impl Fn(&A) -> TokenStream,
) -> Option<TokenStream> {
    let usable: Vec<&A> = addresses
        .iter()
        .filter(|a| direction.allows(access(a)))
        .collect();
    if usable.is_empty() {
        return None;
    }
    let everywhere = usable.iter().find(|a| variant(a).is_none());
    if let (Some(a), true) = (
        everywhere,
        p.variants.is_empty() && usable.iter().all(|a| variant(a).is_none()),
    ) {
        let address = tokens(a);
        return Some(quote! { Some(#address) });
    }
    let specific = usable.iter().filter_map(|a| {
        let index = variants::index(device, variant(a).as_deref()?);
        let address = tokens(a);
        Some(quote! { #index => Some(#address), })
    });
    let fallback = match everywhere {
        Some(a) if p.variants.is_empty() => {
            let address = tokens(a);
            quote! { _ => Some(#address), }
        }
        Some(a) => {
            let address = tokens(a);
            let ids = p.variants.iter().map(|v| variants::index(device, v));
            quote! { #( #ids )|* => Some(#address), _ => None, }
        }
        None => quote! { _ => None, },
    };
    Some(quote! {
        match variant.0 {
            #( #specific )*
            #fallback
        }
    })
}

/// `read_address` / `write_address` body for Modbus.
pub fn modbus(p: &Parameter, device: &Device, direction: Direction) -> Option<TokenStream> {
    body(
        p,
        device,
        &p.modbus,
        direction,
        |a| a.access,
        |a| &a.variant,
        modbus_tokens,
    )
}

/// `read_address` / `write_address` body for CANopen.
pub fn canopen(p: &Parameter, device: &Device, direction: Direction) -> Option<TokenStream> {
    let bytes = p.data_type.bytes();
    body(
        p,
        device,
        &p.canopen,
        direction,
        |a| a.access,
        |a| &a.variant,
        |a| object_tokens(a, bytes),
    )
}
