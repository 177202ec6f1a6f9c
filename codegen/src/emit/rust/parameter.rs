//! A parameter's marker type: its value codec (`Parameter`) and one capability impl per protocol
//! and direction the description allows. What is not allowed has no impl, so it does not compile.

use proc_macro2::{Literal, TokenStream};
use quote::quote;

use super::addresses::{self, Direction};
use super::enums::int_literal;
use super::{doc_attrs, ident, parameter_doc};
use crate::emit::ident as names;
use crate::ir::{Device, Expr, Number, Op, Parameter, Scale};
use crate::validate::scale_inputs_exist::{inputs_readable, readable_canopen, readable_modbus};

fn raw_type(p: &Parameter) -> syn::Type {
    syn::parse_str(&p.data_type.rust_type()).expect("raw types are valid Rust types")
}

fn number(n: Number, p: &Parameter) -> TokenStream {
    match n {
        Number::Int(i) if p.data_type.is_integer() => int_literal(i as i128, p.data_type),
        Number::Int(i) => {
            let lit = Literal::f64_suffixed(i as f64);
            quote! { #lit }
        }
        Number::Float(f) => {
            let lit = Literal::f64_suffixed(f);
            quote! { #lit }
        }
    }
}

/// What users read and write, and how it maps to the raw value.
struct ValueCodec {
    value_type: TokenStream,
    decode: TokenStream,
    encode: TokenStream,
}

fn value_codec(p: &Parameter) -> ValueCodec {
    let raw = raw_type(p);
    if let Some(e) = &p.enumeration {
        let ty = ident(&names::camel(e));
        return ValueCodec {
            value_type: quote! { types::#ty },
            decode: quote! { Ok(types::#ty::from_raw(raw)) },
            encode: quote! { Ok(value.raw()) },
        };
    }
    if let Some(f) = &p.flags {
        let ty = ident(&names::camel(f));
        return ValueCodec {
            value_type: quote! { types::#ty },
            decode: quote! { Ok(types::#ty::from_bits_retain(raw)) },
            encode: quote! { Ok(value.bits()) },
        };
    }
    let unit = p
        .unit
        .as_deref()
        .and_then(drivebus::units::type_name)
        .map(ident);
    match (unit, p.scale.is_some()) {
        (Some(unit), _) => ValueCodec {
            value_type: quote! { ::drivebus::units::#unit },
            decode: quote! { Ok(::drivebus::units::#unit(scale.to_engineering(raw))) },
            encode: quote! { scale.to_raw(Self::NAME, value.0) },
        },
        (None, true) => ValueCodec {
            value_type: quote! { f64 },
            decode: quote! { Ok(scale.to_engineering(raw)) },
            encode: quote! { scale.to_raw(Self::NAME, value) },
        },
        (None, false) => ValueCodec {
            value_type: quote! { #raw },
            decode: quote! { Ok(raw) },
            encode: quote! { Ok(value) },
        },
    }
}

fn fixed_scale(p: &Parameter) -> TokenStream {
    match &p.scale {
        Some(Scale::Fixed {
            numerator,
            denominator,
            offset,
        }) => {
            let (on, od) = (offset.numerator, offset.denominator);
            quote! { const SCALE: ::drivebus::Scale = ::drivebus::Scale::fixed(#numerator, #denominator, #on, #od); }
        }
        _ => quote! {},
    }
}

fn check(p: &Parameter) -> TokenStream {
    let mut checks = Vec::new();
    if let Some(r) = &p.range {
        let (min, max) = (number(r.min, p), number(r.max, p));
        checks.push(quote! { ::drivebus::check::in_range(Self::NAME, *raw, #min, #max)?; });
    }
    if !p.allowed.is_empty() {
        let allowed = p.allowed.iter().map(|n| number(*n, p));
        checks.push(quote! { ::drivebus::check::one_of(Self::NAME, *raw, &[#( #allowed ),*])?; });
    }
    if checks.is_empty() {
        return quote! {};
    }
    let raw = raw_type(p);
    quote! {
        fn check(raw: &#raw) -> Result<(), ::drivebus::ValueError> {
            #( #checks )*
            Ok(())
        }
    }
}

fn expr_tokens(expr: &Expr) -> TokenStream {
    match expr {
        Expr::Number(n, d) => quote! { ::drivebus::Ratio::new(#n, #d)? },
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
            let method = ident(match op {
                Op::Add => "checked_add",
                Op::Sub => "checked_sub",
                Op::Mul => "checked_mul",
                Op::Div => "checked_div",
            });
            quote! { (#a).#method(#b)? }
        }
        Expr::Empty => quote! { None? },
    }
}

/// An inherent `runtime_scale` that reads the factor's inputs and evaluates the expression.
fn runtime_scale(p: &Parameter) -> TokenStream {
    let Some(Scale::Runtime { inputs, ast, .. }) = &p.scale else {
        return quote! {};
    };
    let markers: Vec<_> = inputs.iter().map(|i| ident(&names::camel(i))).collect();
    let vars: Vec<_> = inputs
        .iter()
        .map(|i| ident(&format!("input_{}", names::snake(i))))
        .collect();
    let expr = expr_tokens(ast);
    let name = ident(&names::camel(&p.name));
    quote! {
        impl #name {
            /// Reads the factor's inputs and evaluates the run-time scale expression.
            fn runtime_scale<L: ::drivebus::Link>(
                device: &mut ::drivebus::Device<L>,
            ) -> Result<::drivebus::Scale, ::drivebus::Error>
            where
                #( #markers: ::drivebus::Readable<L::Protocol>, )*
            {
                #( let #vars = ::drivebus::Ratio::from_raw(device.read_raw::<#markers>()?)
                    .ok_or(::drivebus::ValueError::BadScale { parameter: <Self as ::drivebus::Parameter>::NAME })?; )*
                let factor = (|| Some(#expr))()
                    .ok_or(::drivebus::ValueError::BadScale { parameter: <Self as ::drivebus::Parameter>::NAME })?;
                Ok(::drivebus::Scale::factor(factor))
            }
        }
    }
}

fn capability(
    p: &Parameter,
    protocol: TokenStream,
    direction: Direction,
    address_body: Option<TokenStream>,
) -> TokenStream {
    let Some(address_body) = address_body else {
        return quote! {};
    };
    let name = ident(&names::camel(&p.name));
    let address_type = quote! { <#protocol as ::drivebus::Protocol>::Address };
    let (trait_name, address_fn, scale_fn) = match direction {
        Direction::Read => (
            quote! { Readable },
            quote! { read_address },
            quote! { read_scale },
        ),
        Direction::Write => (
            quote! { Writable },
            quote! { write_address },
            quote! { write_scale },
        ),
    };
    let scale_override = matches!(p.scale, Some(Scale::Runtime { .. })).then(|| {
        quote! {
            fn #scale_fn<L: ::drivebus::Link<Protocol = #protocol>>(
                device: &mut ::drivebus::Device<L>,
            ) -> Result<::drivebus::Scale, ::drivebus::Error> {
                Self::runtime_scale(device)
            }
        }
    });
    quote! {
        // Listing the other parameters that do have the capability would drown the message.
        #[diagnostic::do_not_recommend]
        impl ::drivebus::#trait_name<#protocol> for #name {
            #[inline]
            fn #address_fn(variant: ::drivebus::VariantId) -> Option<#address_type> {
                let _ = variant;
                #address_body
            }
            #scale_override
        }
    }
}

pub fn emit(p: &Parameter, device: &Device) -> TokenStream {
    let name = ident(&names::camel(&p.name));
    let docs = doc_attrs(&parameter_doc::text(p, device));
    let param_name = p.name.as_str();
    let raw = raw_type(p);
    let ValueCodec {
        value_type,
        decode,
        encode,
    } = value_codec(p);
    let scale_const = fixed_scale(p);
    let check = check(p);
    let uses_scale = p.unit.is_some() || p.scale.is_some();
    let scale_arg = if uses_scale {
        quote! { scale }
    } else {
        quote! { _scale }
    };
    let modbus = quote! { ::drivebus::modbus::Modbus };
    let canopen = quote! { ::drivebus::canopen::CanOpen };
    // A run-time factor that cannot be read over a protocol leaves the parameter out of it.
    let on_modbus = inputs_readable(p, device, readable_modbus);
    let on_canopen = inputs_readable(p, device, readable_canopen);
    let modbus_address = |d| addresses::modbus(p, device, d).filter(|_| on_modbus);
    let canopen_address = |d| addresses::canopen(p, device, d).filter(|_| on_canopen);
    let capabilities = [
        capability(
            p,
            modbus.clone(),
            Direction::Read,
            modbus_address(Direction::Read),
        ),
        capability(
            p,
            modbus,
            Direction::Write,
            modbus_address(Direction::Write),
        ),
        capability(
            p,
            canopen.clone(),
            Direction::Read,
            canopen_address(Direction::Read),
        ),
        capability(
            p,
            canopen,
            Direction::Write,
            canopen_address(Direction::Write),
        ),
    ];
    let runtime = runtime_scale(p);
    quote! {
        #docs
        #[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
        pub struct #name;

        impl ::drivebus::Parameter for #name {
            const NAME: &'static str = #param_name;
            #scale_const
            type Raw = #raw;
            type Value = #value_type;
            #[inline]
            fn decode(raw: #raw, #scale_arg: ::drivebus::Scale) -> Result<Self::Value, ::drivebus::ValueError> {
                #decode
            }
            #[inline]
            fn encode(value: Self::Value, #scale_arg: ::drivebus::Scale) -> Result<#raw, ::drivebus::ValueError> {
                #encode
            }
            #check
        }

        #[diagnostic::do_not_recommend]
        impl ::drivebus::parameter::ValueOf<#name> for #value_type {
            #[inline]
            fn into_value(self) -> Self {
                self
            }
        }

        #( #capabilities )*
        #runtime
    }
}
