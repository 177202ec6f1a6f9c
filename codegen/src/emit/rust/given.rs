//! What a drive handle is given when it is opened: the product `Model` with its constants
//! (`[[model]]` / `[[constant]]`), and the scale inputs a protocol cannot read (`give_<input>`).
//! Run-time scales obtain parameter inputs through the generated `ScaleInput` trait: read from
//! the drive over a protocol that reaches them, taken from the given values over one that
//! does not.

use proc_macro2::{Literal, TokenStream};
use quote::quote;

use super::read_protocols::read_protocols;
use super::{doc_attrs, ident, raw_type};
use crate::emit::doc;
use crate::ir::{Device, Parameter, Scale};
use crate::names;

/// The parameters read by some run-time scale, each once, in first-use order.
fn parameter_inputs(device: &Device) -> Vec<&Parameter> {
    let mut out: Vec<&Parameter> = Vec::new();
    for p in &device.parameters {
        let Some(Scale::Runtime { inputs, .. }) = &p.scale else {
            continue;
        };
        for input in inputs.iter().filter(|i| !device.is_constant(i)) {
            if let Some(found) = device.parameter(input) {
                if !out.iter().any(|o| o.name == found.name) {
                    out.push(found);
                }
            }
        }
    }
    out
}

/// Whether `input` is read by a run-time scale of a parameter reachable over a protocol that
/// cannot read `input`: then the user gives it.
fn is_given(input: &Parameter, device: &Device) -> bool {
    device.parameters.iter().any(|p| match &p.scale {
        Some(Scale::Runtime { inputs, .. }) if inputs.contains(&input.name) => {
            (!p.modbus.is_empty() && !input.readable_over_modbus())
                || (!p.canopen.is_empty() && !input.readable_over_canopen())
                || (!p.rs232.is_empty() && !input.readable_over_rs232())
        }
        _ => false,
    })
}

/// The `ScaleInput` trait and its impls, inside the generated `params` module.
pub fn scale_inputs(device: &Device) -> TokenStream {
    let inputs = parameter_inputs(device);
    if inputs.is_empty() {
        return quote! {};
    }
    let protocols = read_protocols();
    // Only the protocols the device has: a scale is never computed over another one.
    let reached: [bool; 3] = [
        device.parameters.iter().any(|p| !p.modbus.is_empty()),
        device.parameters.iter().any(|p| !p.canopen.is_empty()),
        device.parameters.iter().any(|p| !p.rs232.is_empty()),
    ];
    let protocols: Vec<_> = protocols
        .into_iter()
        .zip(reached)
        .filter_map(|(protocol, reached)| reached.then_some(protocol))
        .collect();
    let impls = inputs.iter().flat_map(|input| {
        let marker = ident(&names::camel(&input.name));
        let name = input.name.as_str();
        protocols.iter().map(move |(protocol, readable)| {
            let body = if readable(input) {
                quote! { ::drivebus::Ratio::from_raw(device.read_raw::<Self>()?) }
            } else {
                quote! { device.given().get(#name) }
            };
            quote! {
                impl ScaleInput<#protocol> for #marker {
                    fn scale_input<L: ::drivebus::Link<Protocol = #protocol>>(
                        device: &mut ::drivebus::Device<L>,
                        scaled: &'static str,
                    ) -> Result<::drivebus::Ratio, ::drivebus::Error> {
                        Ok((#body).ok_or(::drivebus::ValueError::BadScale { parameter: scaled })?)
                    }
                }
            }
        })
    });
    quote! {
        /// How a run-time scale input is obtained over protocol `P`: read from the drive where
        /// the protocol reaches it, else the value given when the handle was opened.
        pub trait ScaleInput<P: ::drivebus::Protocol> {
            /// The input's exact value; `scaled` names the parameter being scaled, for errors.
            fn scale_input<L: ::drivebus::Link<Protocol = P>>(
                device: &mut ::drivebus::Device<L>,
                scaled: &'static str,
            ) -> Result<::drivebus::Ratio, ::drivebus::Error>;
        }
        #( #impls )*
    }
}

/// The `Model` enum (when the description has models).
fn model_enum(device: &Device) -> TokenStream {
    if device.models.is_empty() {
        return quote! {};
    }
    let variants = device.models.iter().map(|m| {
        let variant = ident(&names::camel(&m.name));
        let docs = doc_attrs(&doc::escape(m.doc.as_deref().unwrap_or(&m.name)));
        quote! { #docs #variant }
    });
    let arms = device.models.iter().map(|m| {
        let variant = ident(&names::camel(&m.name));
        let name = m.name.as_str();
        let constants = m.constants.iter().map(|(c, v)| {
            let (n, d) = (
                Literal::i64_unsuffixed(v.numerator()),
                Literal::i64_unsuffixed(v.denominator()),
            );
            quote! { (#c, match ::drivebus::Ratio::new(#n, #d) { Some(r) => r, None => ::drivebus::Ratio::ZERO }) }
        });
        quote! {
            Self::#variant => {
                const CONSTANTS: &[(&str, ::drivebus::Ratio)] = &[ #( #constants ),* ];
                (#name, CONSTANTS)
            }
        }
    });
    quote! {
        /// The product models of the description; the model fixes the constants run-time scales read.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum Model { #( #variants ),* }

        impl Model {
            const fn table(self) -> (&'static str, &'static [(&'static str, ::drivebus::Ratio)]) {
                match self { #( #arms ),* }
            }
            /// The model's name in the description.
            pub const fn name(self) -> &'static str {
                self.table().0
            }
            /// The model's constants, by name, as exact values.
            pub const fn constants(self) -> &'static [(&'static str, ::drivebus::Ratio)] {
                self.table().1
            }
        }
    }
}

/// `Model`, plus the handle's `with_model` / `set_model` and `give_<input>` methods.
pub fn emit(device: &Device) -> TokenStream {
    let given: Vec<&Parameter> = parameter_inputs(device)
        .into_iter()
        .filter(|p| is_given(p, device))
        .collect();
    if device.device.is_profile || (device.models.is_empty() && given.is_empty()) {
        return quote! {};
    }
    let handle = ident(&names::camel(&device.device.handle));
    let model_methods = (!device.models.is_empty()).then(|| {
        quote! {
            /// Opens the handle for product `model`: its constants scale the values that read them.
            #[must_use]
            pub fn with_model(mut self, model: Model) -> Self {
                self.set_model(model);
                self
            }
            /// Selects the product model whose constants scale the values that read them.
            pub fn set_model(&mut self, model: Model) {
                for (name, value) in model.constants() {
                    // Validation keeps the names within `drivebus::given::MAX_GIVEN`.
                    let _stored = self.device.given_mut().set(name, *value);
                }
            }
        }
    });
    let give = given.iter().map(|p| {
        let method = ident(&format!("give_{}", names::snake(&p.name)));
        let raw = raw_type(p.data_type);
        let name = p.name.as_str();
        let marker = names::camel(&p.name);
        let docs = doc_attrs(&format!(
            "Gives the raw value of [`params::{marker}`], a run-time scale input that some protocol of this handle cannot read; the scales read it from here there."
        ));
        quote! {
            #docs
            #[must_use]
            pub fn #method(mut self, raw: #raw) -> Self {
                if let Some(value) = ::drivebus::Ratio::from_raw(raw) {
                    let _stored = self.device.given_mut().set(#name, value);
                }
                self
            }
        }
    });
    let model = model_enum(device);
    quote! {
        #model
        impl<L: ::drivebus::Link> #handle<L> {
            #model_methods
            #( #give )*
        }
    }
}
