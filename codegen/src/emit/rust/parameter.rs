//! A parameter's marker type, and one `drivebus::parameter!` declaration of its value codec and of
//! a capability per protocol and direction the description allows. What is not allowed has no
//! impl, so it does not compile. The declaration is opaque to the generator's own parse and
//! print, and writes the impls once in `drivebus`: both keep generation and compilation fast.
//! Paths go through the `db` alias of `::drivebus` that the `params` module declares.

use proc_macro2::{Ident, Literal, TokenStream};
use quote::quote;

use super::addresses::{self, Direction};
use super::enums::int_literal;
use super::{concat, doc_attrs, ident, layout, parameter_doc, raw_type};
use crate::ir::{DataType, Device, Expr, Number, Op, Parameter, Scale, ValueType};
use crate::names;

/// A raw value as a literal of the parameter's raw type (validation keeps floats finite and
/// within that type's width).
fn number(n: Number, p: &Parameter) -> TokenStream {
    let lit = match n {
        Number::Int(i) if p.data_type.is_integer() => return int_literal(i as i128, p.data_type),
        // Validation keeps a boolean's values to 0 and 1.
        Number::Int(i) if p.data_type == DataType::Bool => {
            let value = i != 0;
            return quote! { #value };
        }
        // Unsuffixed: the macro's checks compare with the raw value, which fixes the type.
        n if p.data_type == DataType::F32 => Literal::f32_unsuffixed(n.as_f64() as f32),
        n => Literal::f64_unsuffixed(n.as_f64()),
    };
    quote! { #lit }
}

/// The Rust type of a parameter's value, naming generated enums and flags through `types` (the
/// path of the generated `types` module from where the type is written).
pub(super) fn value_type(p: &Parameter, types: &TokenStream) -> TokenStream {
    match p.value_type() {
        ValueType::Enum(name) | ValueType::Flags(name) => {
            let ty = ident(&names::camel(name));
            quote! { #types::#ty }
        }
        ValueType::Unit(unit) => {
            let unit = ident(unit);
            quote! { ::drivebus::units::#unit }
        }
        ValueType::Scaled => quote! { f64 },
        ValueType::Raw(data_type) => raw_type(data_type),
    }
}

/// The `drivebus::codec` marker that converts a parameter's raw and engineering values.
fn codec(p: &Parameter) -> Ident {
    ident(match p.value_type() {
        ValueType::Enum(_) => "Enumerated",
        ValueType::Flags(_) => "Flags",
        ValueType::Unit(_) => "InUnit",
        ValueType::Scaled => "Scaled",
        ValueType::Raw(_) => "Plain",
    })
}

/// A ratio's numerator and denominator as literals (a negative numerator keeps its sign).
fn ratio_tokens(ratio: drivebus_model::Ratio) -> (TokenStream, Literal) {
    let numerator = int_literal(i128::from(ratio.numerator()), DataType::Signed(8));
    (numerator, Literal::i64_unsuffixed(ratio.denominator()))
}

/// The optional clauses of the declaration: fixed scale, range and allowed raw values.
fn clauses(p: &Parameter) -> TokenStream {
    let scale = match &p.scale {
        Some(Scale::Fixed(scale)) => {
            let (n, d) = ratio_tokens(scale.factor);
            let offset = (scale.offset != drivebus_model::Ratio::ZERO).then(|| {
                let (on, od) = ratio_tokens(scale.offset);
                quote! { , offset = #on / #od }
            });
            quote! { , scale = #n / #d #offset }
        }
        _ => quote! {},
    };
    let range = p.range.as_ref().map(|r| {
        let (min, max) = (number(r.min, p), number(r.max, p));
        quote! { , range(#min, #max) }
    });
    let allowed = (!p.allowed.is_empty()).then(|| {
        let allowed = p.allowed.iter().map(|n| number(*n, p));
        quote! { , one_of[#( #allowed ),*] }
    });
    let stops = p.stops.as_ref().map(|stops| {
        let stops = stops_tokens(stops.view());
        quote! { , stops(#stops) }
    });
    quote! { #scale #range #allowed #stops }
}

/// `always`, or `mask => value, ...` with the masks and values in hex, as a manual prints them.
fn stops_tokens(stops: drivebus_model::Stops<'_>) -> TokenStream {
    let hex = |v: u64| syn::LitInt::new(&format!("{v:#06x}"), proc_macro2::Span::call_site());
    match stops {
        drivebus_model::Stops::Never => quote! {},
        drivebus_model::Stops::Always => quote! { always },
        drivebus_model::Stops::Matching(patterns) => {
            let patterns = patterns.iter().map(|p| {
                let (mask, value) = (hex(p.mask), hex(p.value));
                quote! { #mask => #value }
            });
            quote! { #( #patterns ),* }
        }
    }
}

fn op_method(op: Op) -> &'static str {
    match op {
        Op::Add => "checked_add",
        Op::Sub => "checked_sub",
        Op::Mul => "checked_mul",
        Op::Div => "checked_div",
    }
}

fn expr_tokens(expr: &Expr) -> TokenStream {
    match expr {
        Expr::Number(ratio) => {
            let (n, d) = (ratio.numerator(), ratio.denominator());
            let (n, d) = (super::unsuffixed(n.into()), super::unsuffixed(d.into()));
            quote! { ::drivebus::Ratio::new(#n, #d)? }
        }
        Expr::Parameter(name) => {
            let var = ident(&format!("input_{}", names::snake(name)));
            quote! { #var }
        }
        Expr::Negate(a) => {
            let a = expr_tokens(a);
            quote! { ::drivebus::Ratio::ZERO.checked_sub(#a)? }
        }
        Expr::Binary(a, op, b) => {
            let (a, b) = (expr_tokens(a), expr_tokens(b));
            let method = ident(op_method(*op));
            quote! { (#a).#method(#b)? }
        }
        Expr::Empty => quote! { None? },
    }
}

/// An inherent `runtime_scale` that obtains the factor's inputs — parameters through
/// `ScaleInput` (read, or given where the protocol cannot read them), constants from the model the
/// handle was opened with — and evaluates the run-time scale expression.
fn runtime_scale(p: &Parameter, name: &Ident, device: &Device) -> TokenStream {
    let Some(Scale::Runtime { inputs, ast, .. }) = &p.scale else {
        return quote! {};
    };
    let (constants, parameters): (Vec<&String>, Vec<&String>) =
        inputs.iter().partition(|i| device.is_constant(i));
    let markers: Vec<_> = parameters.iter().map(|i| ident(&names::camel(i))).collect();
    let var = |i: &String| ident(&format!("input_{}", names::snake(i)));
    let (parameter_vars, constant_vars): (Vec<_>, Vec<_>) = (
        parameters.iter().map(|i| var(i)).collect(),
        constants.iter().map(|i| var(i)).collect(),
    );
    let constant_names = constants.iter().map(|c| c.as_str());
    let expr = expr_tokens(ast);
    quote! {
        impl #name {
            /// Obtains the factor's inputs and evaluates the run-time scale expression.
            // Every operation is checked (`?`), the last one included.
            #[allow(clippy::needless_question_mark)]
            fn runtime_scale<L: ::drivebus::Link>(
                device: &mut ::drivebus::Device<L>,
            ) -> Result<::drivebus::Scale, ::drivebus::Error>
            where
                #( #markers: ScaleInput<L::Protocol>, )*
            {
                let bad = || ::drivebus::ValueError::BadScale { parameter: <Self as ::drivebus::Parameter>::NAME };
                #( let #parameter_vars = <#markers as ScaleInput<L::Protocol>>::scale_input(device, <Self as ::drivebus::Parameter>::NAME)?; )*
                #( let #constant_vars = device.given().get(#constant_names).ok_or_else(bad)?; )*
                let factor = (|| Some(#expr))().ok_or_else(bad)?;
                Ok(::drivebus::Scale::factor(factor))
            }
        }
    }
}

/// `; read modbus (input 0x0064)`: one capability clause, if the direction is allowed; a write
/// names the parameters that bound it (`[bounds: max = MaximumOutputFrequency]`).
fn capability(
    p: &Parameter,
    protocol: &str,
    direction: Direction,
    placement: Option<TokenStream>,
) -> Option<TokenStream> {
    let placement = placement?;
    let protocol = ident(protocol);
    let bounds = match direction {
        Direction::Write => super::bounds::clause(p),
        Direction::Read | Direction::SafetyWrite => TokenStream::new(),
    };
    let direction = ident(match direction {
        Direction::Read => "read",
        Direction::Write => "write",
        Direction::SafetyWrite => "safety_write",
    });
    let runtime = matches!(p.scale, Some(Scale::Runtime { .. })).then(|| quote! { runtime });
    Some(quote! { ; #direction #protocol #placement #bounds #runtime })
}

pub fn emit(p: &Parameter, device: &Device) -> TokenStream {
    emit_as(p, &ident(&names::camel(&p.name)), device)
}

/// [`emit`] with the marker type named `name` (a sub-index run's marker is not named as the
/// parameter: the run's accessor type in `indexed` is).
pub fn emit_as(p: &Parameter, name: &Ident, device: &Device) -> TokenStream {
    let docs = doc_attrs(&parameter_doc::text(p, device));
    let aliases = parameter_doc::aliases(p);
    let param_name = p.name.as_str();
    let raw = raw_type(p.data_type);
    let (value_type, codec) = (value_type(p, &quote! { types }), codec(p));
    let clauses = clauses(p);
    let capabilities = [Direction::Read, Direction::Write]
        .into_iter()
        .flat_map(|d| {
            [
                capability(p, "modbus", d, addresses::modbus(p, device, d)),
                capability(p, "canopen", d, addresses::canopen(p, device, d)),
                capability(p, "rs232", d, addresses::rs232(p, device, d)),
            ]
        })
        .flatten()
        .chain(capability(
            p,
            "canopen",
            Direction::SafetyWrite,
            addresses::canopen(p, device, Direction::SafetyWrite),
        ))
        .collect::<Vec<_>>();
    // Written out after printing (see `layout`): one line, or one clause per line.
    let invocation = layout::clauses_call(
        "::drivebus::parameter",
        quote! { #name = #param_name: #raw => #value_type, #codec #clauses #( #capabilities )* },
    );
    let declaration = quote! {
        #aliases
        pub struct #name;
        #invocation
    };
    // Without a capability nothing would call the scale (an unused function warns).
    let scale = match capabilities.is_empty() {
        true => quote! {},
        false => runtime_scale(p, name, device),
    };
    concat([docs, declaration, scale])
}

#[cfg(test)]
mod tests {
    use crate::test_support::device;

    /// A parameter scaled by `resolution`, whose own access is `access`.
    fn scaled_by_resolution(access: &str) -> String {
        let device = device(&format!(
            r#"
[[parameter]]
name = "resolution"
type = "u32"
modbus = {{ table = "holding", address = 1, words = 2, access = "{access}" }}
source = {{ doc = "m", line = 1 }}

[[parameter]]
name = "speed"
type = "i32"
scale = {{ expr = "2 * resolution" }}
modbus = {{ table = "holding", address = 3, words = 2 }}
source = {{ doc = "m", line = 1 }}
"#
        ));
        super::emit(device.parameter("speed").unwrap(), &device).to_string()
    }

    #[test]
    fn a_runtime_scale_is_emitted_whether_or_not_its_input_can_be_read() {
        assert!(scaled_by_resolution("rw").contains("runtime_scale"));
        // The input cannot be read: its value is given when the handle is opened.
        assert!(scaled_by_resolution("w").contains("runtime_scale"));
    }
}
