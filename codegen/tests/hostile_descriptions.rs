//! A description full of quotes, comment terminators, braces, keywords, code and doc-test fences
//! must generate code that compiles, defines nothing but what the description declares, and has no
//! doctest to run.

mod support;

use std::path::Path;

use proc_macro2::{TokenStream, TokenTree};
use quote::ToTokens;
use support::crate_build::{build_and_doctest, no_std_lib};

fn generate(path: &str) -> String {
    let checked = drivegen::check(Path::new(path));
    let device = checked
        .device
        .as_ref()
        .unwrap_or_else(|| panic!("{}", checked.render()));
    drivegen::emit::rust::generate(device, "hostile.toml")
}

#[test]
fn hostile_names_and_docs_cannot_inject_items() {
    let source = generate("tests/fixtures/hostile.toml");
    let file = syn::parse_file(&source).expect("generated code parses");
    let fn_names: Vec<String> = file
        .items
        .iter()
        .filter_map(|item| match item {
            syn::Item::Fn(f) => Some(f.sig.ident.to_string()),
            _ => None,
        })
        .collect();
    assert!(
        fn_names.is_empty(),
        "no free functions are generated: {fn_names:?}"
    );
    assert!(!source.contains("fn injected"), "a doc or name became code");
    for doc in doc_texts(&source) {
        for line in doc.lines() {
            assert!(
                !line.trim_start().starts_with("```"),
                "a doc line opens a code block (doctest): {line:?}"
            );
            assert!(
                !line.starts_with("     "),
                "an indented doc line would be a doctest: {line:?}"
            );
        }
    }
}

/// Every `#[doc = "..."]` text of the generated code (doc comments included), unescaped.
fn doc_texts(source: &str) -> Vec<String> {
    fn walk(tokens: TokenStream, out: &mut Vec<String>) {
        let tokens: Vec<TokenTree> = tokens.into_iter().collect();
        for window in tokens.windows(3) {
            if let [TokenTree::Ident(key), TokenTree::Punct(eq), TokenTree::Literal(text)] = window
            {
                if key == "doc" && eq.as_char() == '=' {
                    let lit: syn::LitStr = syn::parse2(text.to_token_stream()).unwrap();
                    out.push(lit.value());
                }
            }
        }
        for token in tokens {
            if let TokenTree::Group(group) = token {
                walk(group.stream(), out);
            }
        }
    }
    let mut out = Vec::new();
    walk(source.parse().expect("generated code lexes"), &mut out);
    assert!(!out.is_empty(), "the generated code has docs");
    out
}

/// Builds the generated code in a scratch crate with `#![deny(warnings)]` and runs its doctests.
#[test]
fn hostile_description_compiles_without_warnings_and_without_doctests() {
    let source = generate("tests/fixtures/hostile.toml");
    let built = build_and_doctest("hostile", &no_std_lib(&source));
    assert!(
        built.success,
        "generated code does not build:\n{}",
        built.stderr
    );
    assert!(
        built.stdout.contains("running 0 tests"),
        "a description doc became a doctest:\n{}",
        built.stdout
    );
}

/// Integer types at their edges (ranges spanning the type, defaults at both ends, extreme
/// scales and enum values) and names that differ only in Unicode normalisation generate code
/// that compiles without warnings.
#[test]
fn numbers_at_type_edges_generate_code_that_compiles() {
    let source = generate("tests/fixtures/hostile_numbers.toml");
    let file = syn::parse_file(&source).expect("generated code parses");
    assert!(!file.items.is_empty());
    let built = build_and_doctest("hostile_numbers", &no_std_lib(&source));
    assert!(
        built.success,
        "generated code does not build:\n{}",
        built.stderr
    );
}

/// Nesting as deep as a TOML parser's stack allows is a diagnostic, not a stack overflow.
#[test]
fn deeply_nested_toml_is_a_diagnostic() {
    let dir = std::env::temp_dir().join(format!("drivegen-nested-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, open, close) in [("arrays", "[", "]"), ("tables", "{ a = ", " }")] {
        let depth = 100_000;
        let text = format!(
            "format = 1\nx = {}1{}\n",
            open.repeat(depth),
            close.repeat(depth)
        );
        let path = dir.join(format!("{name}.toml"));
        std::fs::write(&path, text).unwrap();
        let checked = drivegen::check(&path);
        assert!(checked.device.is_none(), "{name}: nesting accepted");
        assert!(
            checked.render().contains("error[syntax]"),
            "{name}: {}",
            checked.render()
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
