//! `MODBUS_READ_BLOCKS`: the reads a device answers beyond its read limit (`[modbus]
//! read_blocks`), as register spans for hand-written helpers and the request planner.

use proc_macro2::{Literal, TokenStream};
use quote::quote;

use super::addresses::hex;
use crate::ir::{Device, Table};

pub fn emit(device: &Device) -> TokenStream {
    let Some(caps) = device.modbus.as_ref().filter(|c| !c.read_blocks.is_empty()) else {
        return TokenStream::new();
    };
    let spans = caps.read_blocks.iter().map(|b| {
        let table = match b.table {
            Table::Input => quote! { input },
            Table::Holding => quote! { holding },
        };
        let (start, count) = (hex(b.address), Literal::u16_unsuffixed(b.words));
        quote! { ::drivebus::modbus::RegisterSpan::#table(#start, #count) }
    });
    quote! {
        /// Reads the device answers beyond `MODBUS_LIMITS.max_read_registers`, exactly as
        /// listed (table, first register, count), from the description's `[modbus] read_blocks`.
        pub const MODBUS_READ_BLOCKS: &[::drivebus::modbus::RegisterSpan] = &[#( #spans ),*];
    }
}
