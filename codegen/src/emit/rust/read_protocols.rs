//! The protocols a generated crate can read a parameter over: each protocol marker type with the
//! test of whether a parameter is readable over it. Code generated per protocol (scale inputs,
//! identity checks) walks this one list.

use proc_macro2::TokenStream;
use quote::quote;

use crate::ir::Parameter;

/// Whether a parameter is readable over a protocol.
pub type Readable = fn(&Parameter) -> bool;

/// Modbus, CANopen and Kinco RS-232, in that order, with their readability tests.
pub fn read_protocols() -> [(TokenStream, Readable); 3] {
    [
        (
            quote! { ::drivebus::modbus::Modbus },
            Parameter::readable_over_modbus,
        ),
        (
            quote! { ::drivebus::canopen::CanOpen },
            Parameter::readable_over_canopen,
        ),
        (
            quote! { ::drivebus::rs232::Rs232 },
            Parameter::readable_over_rs232,
        ),
    ]
}
