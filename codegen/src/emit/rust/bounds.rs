//! Bounds set by other parameters (`bounds = { min, max, magnitude }`): the
//! `[bounds: magnitude = FullScaleVelocity]` clause of a write capability, which becomes the
//! `Writable::BOUNDS` the handle's every write checks (reading the bounds over the same link
//! first). There is no second, bounded write method to remember.

use drivebus_model::model::Described;
use drivebus_model::Bound;
use proc_macro2::TokenStream;
use quote::quote;

use super::ident;
use crate::ir::Parameter;
use crate::names;

/// The bounds clause of a write capability of `p`, or nothing when no parameter bounds it.
pub(super) fn clause(p: &Parameter) -> TokenStream {
    let bounds: Vec<TokenStream> = p
        .bounded_by()
        .each()
        .map(|(bound, by)| {
            let bound = ident(match bound {
                Bound::Min => "min",
                Bound::Max => "max",
                Bound::Magnitude => "magnitude",
            });
            let by = ident(&names::camel(by));
            quote! { #bound = #by }
        })
        .collect();
    if bounds.is_empty() {
        return TokenStream::new();
    }
    quote! { [bounds: #( #bounds ),*] }
}
