//! Members described once over a run of sub-indices (`subindex = "1..=8"`), as device-driver emits
//! a repeated register: ONE marker in `params` (an ordinary parameter placed at the run's first
//! sub-index, plus `drivebus::indexed::Run` with the run's bounds), one alias in `indexed` of
//! `drivebus::indexed::Indexed` over it, and one handle method `drive.<name>(subindex)`. A
//! sub-index outside the run is refused with `ValueError::OutOfRange` before anything is sent.
//! One member is a type where a type is needed: `drivebus::indexed::At<params::<Run>, N>`.

use proc_macro2::{Ident, Literal, TokenStream};
use quote::quote;

use super::{concat, doc_attrs, ident, parameter};
use crate::emit::doc;
use crate::ir::{Device, IndexedParameter, Parameter};
use crate::names;

/// Whether `p` is a member of a run, reached through its run's marker and indexed accessor.
pub(super) fn is_member(p: &Parameter, device: &Device) -> bool {
    device
        .indexed
        .iter()
        .any(|run| run.members.contains(&p.name))
}

/// The run's marker for `params`: the run's one parameter (its doc table gives the whole run's
/// sub-indices) and its bounds.
pub(super) fn marker_type(run: &IndexedParameter, device: &Device) -> TokenStream {
    let ty = marker(run);
    let declaration = parameter::emit_as(&run.parameter, &ty, device);
    let (first, last) = (
        Literal::u8_unsuffixed(run.first),
        Literal::u8_unsuffixed(run.last),
    );
    quote! {
        #declaration
        impl ::drivebus::indexed::Run for #ty {
            const FIRST: u8 = #first;
            const LAST: u8 = #last;
        }
    }
}

/// The ident of the run's marker type in `params`.
fn marker(run: &IndexedParameter) -> Ident {
    ident(&names::camel(&run.marker_name()))
}

/// The `indexed` module with one accessor type per run, and the handle methods.
pub(super) fn emit(device: &Device, handle: &Ident) -> TokenStream {
    if device.indexed.is_empty() {
        return quote! {};
    }
    let types = concat(device.indexed.iter().map(accessor_type));
    let methods = device.indexed.iter().map(handle_method);
    quote! {
        /// Accessors of members described once over a run of sub-indices: `drive.<name>(n)`.
        pub mod indexed {
            #[allow(unused_imports)]
            use super::params;
            #types
        }

        // No `Link` bound: the same methods serve the async handle (`Async<L>`), whose
        // `Indexed` has the awaited read and write.
        impl<L> #handle<L> {
            #( #methods )*
        }
    }
}

fn handle_method(run: &IndexedParameter) -> TokenStream {
    let method = ident(&names::method(&run.name));
    let ty = ident(&names::camel(&run.name));
    let docs = doc_attrs(&format!(
        "{} Sub-indices {}..={} of object 0x{:04X}: [`indexed::{ty}`].",
        summary(run),
        run.first,
        run.last,
        run.index,
    ));
    quote! {
        #docs
        pub fn #method(&mut self, subindex: u8) -> indexed::#ty<'_, L> {
            ::drivebus::indexed::Indexed::new(&mut self.device, subindex)
        }
    }
}

fn summary(run: &IndexedParameter) -> String {
    doc::summary(run.doc.as_deref(), &run.name)
}

fn accessor_type(run: &IndexedParameter) -> TokenStream {
    let (ty, marker) = (ident(&names::camel(&run.name)), marker(run));
    let docs = doc_attrs(&format!(
        "{} Sub-indices {}..={} of object 0x{:04X}, marker [`params::{marker}`].",
        summary(run),
        run.first,
        run.last,
        run.index,
    ));
    // An alias, not a wrapper: `Indexed` reads and writes what the marker's traits allow (a safety
    // run's marker is not `Writable`, so its accessor has no setter).
    quote! {
        #docs
        pub type #ty<'d, L> = ::drivebus::indexed::Indexed<'d, L, params::#marker>;
    }
}

#[cfg(test)]
mod tests {
    use crate::test_support::device;

    const RUN: &str = r#"
[[parameter]]
name = "sls_limit"
doc = "SLS limit."
type = "u32"
canopen = { index = 0x6693, subindex = "1..=200", access = "rw" }
source = { doc = "m", line = 1 }
"#;

    #[test]
    fn a_run_is_one_marker_and_one_accessor_without_a_type_or_arm_per_sub_index() {
        let code = crate::emit::rust::generate(&device(RUN), "t");
        assert_eq!(code.matches("pub struct SlsLimitRun;").count(), 1, "{code}");
        assert!(!code.contains("SlsLimit1"), "{code}");
        assert!(code.contains("impl ::drivebus::indexed::Run for SlsLimitRun"));
        assert!(code.contains("const LAST: u8 = 200;"));
        assert!(code.contains("object `0x6693:1..=200`"));
        assert!(code.contains("pub fn sls_limit(&mut self, subindex: u8)"));
        // One alias over the runtime's accessor, and nothing per sub-index.
        assert!(code.contains(
            "pub type SlsLimit<'d, L> = ::drivebus::indexed::Indexed<'d, L, params::SlsLimitRun>;"
        ));
        assert!(!code.contains("=> self"), "{code}");
    }
}
