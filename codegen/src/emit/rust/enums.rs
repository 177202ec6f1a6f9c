//! Open enumerations: a newtype over the raw integer with one associated constant per documented
//! value. Unknown values survive a read; building one from a number goes through `TryFrom`. The
//! impls every enumeration shares come from `drivebus::open_enum!`.

use proc_macro2::{Literal, TokenStream};
use quote::quote;

use super::{doc_attrs, ident, layout, raw_type};
use crate::emit::doc;
use crate::ir::{DataType, Enum, EnumValue, ValueClass};
use crate::names;

/// An integer literal of the given type, so negative and wide values print exactly.
pub fn int_literal(value: i128, ty: DataType) -> TokenStream {
    let lit = match ty.rust_scalar().unwrap_or_default() {
        "u8" => Literal::u8_unsuffixed(value as u8),
        "u16" => Literal::u16_unsuffixed(value as u16),
        "u32" => Literal::u32_unsuffixed(value as u32),
        "u64" => Literal::u64_unsuffixed(value as u64),
        _ => Literal::i128_unsuffixed(value.abs()),
    };
    if value < 0 {
        quote! { -#lit }
    } else {
        quote! { #lit }
    }
}

pub fn emit(e: &Enum) -> TokenStream {
    let name = ident(&names::camel(&e.name));
    let raw = raw_type(e.data_type);
    let intro = doc::escape(e.doc.as_deref().unwrap_or(&e.name));
    let docs = doc_attrs(&format!(
        "{intro}\n\nOpen enumeration over `{}`: values the description does not list survive reads.",
        e.data_type.name()
    ));
    let consts: Vec<_> = e
        .values
        .iter()
        .map(|v| ident(&names::constant(&v.name)))
        .collect();
    let values: Vec<_> = e
        .values
        .iter()
        .map(|v| int_literal(v.value as i128, e.data_type))
        .collect();
    let value_names = e.values.iter().map(|v| v.name.as_str());
    let error_attributes = error_attributes(e);
    // The value itself is in the constant's definition; the doc says what it means.
    let const_docs = e.values.iter().map(|v| {
        let meaning = match &v.doc {
            Some(text) => doc::escape(text),
            None => format!("The value `{}`.", v.value),
        };
        let attributes = error_attribute_doc(v, &meaning);
        doc_attrs(&format!("{meaning}{attributes}"))
    });
    let open_enum = layout::list_call("::drivebus::open_enum", quote! { #name: #raw });
    quote! {
        #docs
        #[derive(Clone, Copy, PartialEq, Eq, Hash)]
        pub struct #name(#raw);

        impl #name {
            #( #const_docs pub const #consts: Self = Self(#values); )*
            /// Every documented value.
            pub const VALUES: &'static [Self] = &[#( Self::#consts ),*];

            /// The description's name for the value, `None` for an undocumented value.
            pub const fn name(self) -> Option<&'static str> {
                match self.0 {
                    #( #values => Some(#value_names), )*
                    _ => None,
                }
            }
            #error_attributes
        }

        #open_enum
    }
}

/// `class()`, `led_code()` and `meaning()`, each only when some value of the enum carries that
/// attribute, so plain enumerations keep a small API.
fn error_attributes(e: &Enum) -> TokenStream {
    let class = attribute_fn(
        e,
        quote! {
            /// Whether the code is a fault (the drive stops) or a warning; `None` when the
            /// description gives no class for the value (or does not list it).
            pub const fn class(self) -> Option<::drivebus::ErrorClass>
        },
        |v| {
            v.class.map(|class| match class {
                ValueClass::Fault => quote! { ::drivebus::ErrorClass::Fault },
                ValueClass::Warning => quote! { ::drivebus::ErrorClass::Warning },
            })
        },
    );
    let led = attribute_fn(
        e,
        quote! {
            /// The LED blink code `(first, second)` the drive shows for this value; `None` when
            /// the manual gives none.
            pub const fn led_code(self) -> Option<(u8, u8)>
        },
        |v| {
            v.led.map(|[first, second]| {
                let (first, second) = (
                    Literal::u8_unsuffixed(first),
                    Literal::u8_unsuffixed(second),
                );
                quote! { (#first, #second) }
            })
        },
    );
    let meaning = attribute_fn(
        e,
        quote! {
            /// What the value means and what to do about it, from the manual's table.
            pub const fn meaning(self) -> Option<&'static str>
        },
        |v| v.meaning.as_deref().map(|text| quote! { #text }),
    );
    quote! { #class #led #meaning }
}

/// The error-code attributes of one value as a rustdoc paragraph after its `doc`; empty when it
/// has none. The meaning is left out where the doc already begins with it.
fn error_attribute_doc(v: &EnumValue, doc: &str) -> String {
    let mut text = String::new();
    if let Some(meaning) = v.meaning.as_deref().map(doc::escape) {
        if !doc.starts_with(meaning.trim_end_matches('.')) {
            text += &format!("\n\n{meaning}");
        }
    }
    if let Some(class) = v.class {
        let class = match class {
            ValueClass::Fault => "fault",
            ValueClass::Warning => "warning",
        };
        text += &format!(" Class: {class}.");
    }
    if let Some([first, second]) = v.led {
        text += &format!(" LED code: {first},{second}.");
    }
    text
}

/// A `const fn` mapping every value that has the attribute to `Some(attribute)`; nothing when no
/// value has it.
fn attribute_fn(
    e: &Enum,
    signature: TokenStream,
    attribute: impl Fn(&EnumValue) -> Option<TokenStream>,
) -> TokenStream {
    let arms: Vec<_> = e
        .values
        .iter()
        .filter_map(|v| {
            let value = int_literal(v.value as i128, e.data_type);
            attribute(v).map(|a| quote! { #value => Some(#a), })
        })
        .collect();
    if arms.is_empty() {
        return TokenStream::new();
    }
    quote! {
        #signature {
            match self.0 {
                #( #arms )*
                _ => None,
            }
        }
    }
}
