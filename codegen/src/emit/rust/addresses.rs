//! Per-protocol placements: which address a parameter is read or written at, per variant.

use proc_macro2::{Literal, TokenStream};
use quote::quote;

use crate::ir::{Access, Device, ModbusAddress, ObjectAddress, Parameter, Table, WordOrder};

/// Read, write, or the deliberate safety-function write (`safety = true` parameters).
#[derive(Clone, Copy)]
pub enum Direction {
    Read,
    Write,
    SafetyWrite,
}

impl Direction {
    fn allows(self, access: Access) -> bool {
        match self {
            Direction::Read => access.read,
            Direction::Write | Direction::SafetyWrite => access.write,
        }
    }
}

/// A hexadecimal literal, as the manuals write addresses.
pub(super) fn hex(value: u16) -> Literal {
    format!("0x{value:04X}")
        .parse()
        .expect("a hexadecimal integer is a literal")
}

/// `(input 0x0064)`, or `(holding 0x0010, 2 words, LowFirst)` where the value spans several
/// registers or is text (only then does the order matter), in `drivebus::parameter!` syntax.
fn modbus_tokens(a: &ModbusAddress) -> TokenStream {
    let table = match a.table {
        Table::Input => quote! { input },
        Table::Holding => quote! { holding },
    };
    let address = hex(a.address);
    // One register of a number has no word order to tell; text keeps its byte order.
    if a.words == 1 && a.word_order != WordOrder::Text {
        return quote! { (#table #address) };
    }
    let order = match a.word_order {
        WordOrder::HighFirst => quote! { HighFirst },
        WordOrder::LowFirst => quote! { LowFirst },
        WordOrder::Text => quote! { Text },
    };
    let words = Literal::u16_unsuffixed(a.words);
    quote! { (#table #address, #words words, #order) }
}

/// `(0x6040 sub 0, 2 bytes)`: index, subindex and size, in `drivebus::parameter!` syntax.
fn object_tokens(a: &ObjectAddress, bytes: u16) -> TokenStream {
    let (index, subindex) = (hex(a.index), Literal::u8_unsuffixed(a.subindex));
    let bytes = Literal::u16_unsuffixed(bytes);
    quote! { (#index sub #subindex, #bytes bytes) }
}

/// Where a parameter is for one direction, in `drivebus::parameter!` syntax: one address
/// everywhere, or a list with a slot per variant (`_` where absent). `None` if no address allows
/// the direction (then the capability trait is not implemented at all).
fn placement<A>(
    p: &Parameter,
    device: &Device,
    addresses: &[A],
    direction: Direction,
    access: impl Fn(&A) -> Access,
    variant: impl Fn(&A) -> &Option<String>,
    tokens: impl Fn(&A) -> TokenStream,
) -> Option<TokenStream> {
    // Safety parameters get no write placement on any protocol: only the deliberate safety
    // write changes them (`Parameter::is_safety`).
    match direction {
        Direction::Write if p.is_safety() => return None,
        Direction::SafetyWrite if !p.is_safety_function_parameter() => return None,
        _ => {}
    }
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
        return Some(address);
    }
    let per_variant = device.variants.iter().map(|v| {
        let specific = usable
            .iter()
            .find(|a| variant(a).as_deref() == Some(v.name.as_str()));
        let general = everywhere.filter(|_| p.variants.is_empty() || p.variants.contains(&v.name));
        specific
            .or(general)
            .map_or_else(|| quote! { _ }, |a| tokens(a))
    });
    Some(quote! { [#( #per_variant ),*] })
}

/// The Modbus placement for reads or writes.
pub fn modbus(p: &Parameter, device: &Device, direction: Direction) -> Option<TokenStream> {
    placement(
        p,
        device,
        &p.modbus,
        direction,
        |a| a.access,
        |a| &a.variant,
        modbus_tokens,
    )
}

/// The CANopen placement for reads or writes.
pub fn canopen(p: &Parameter, device: &Device, direction: Direction) -> Option<TokenStream> {
    objects(p, device, &p.canopen, direction)
}

/// The Kinco RS-232 placement for reads or writes: object addresses, as on CANopen.
pub fn rs232(p: &Parameter, device: &Device, direction: Direction) -> Option<TokenStream> {
    objects(p, device, &p.rs232, direction)
}

fn objects(
    p: &Parameter,
    device: &Device,
    addresses: &[ObjectAddress],
    direction: Direction,
) -> Option<TokenStream> {
    let bytes = p.data_type.bytes();
    placement(
        p,
        device,
        addresses,
        direction,
        |a| a.access,
        |a| &a.variant,
        |a| object_tokens(a, bytes),
    )
}
