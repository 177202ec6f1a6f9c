//! The layout prettyplease cannot give: macro invocations written as a person would write them,
//! and doc lines wrapped at 100 columns.
//!
//! prettyplease prints a macro's body as a stream of tokens broken wherever the line is full
//! (`scale = 1 /` newline `100`). So the emitter leaves a placeholder item `__drivegen_text!(N);`
//! where a `drivebus` macro is invoked, and [`finish`] replaces it after printing, at the
//! placeholder's indentation: on one line when it fits, otherwise one clause per line. The calls
//! wait in a per-thread list between the two steps, so the emitters keep returning plain tokens.

use std::cell::RefCell;
use std::fmt::Write as _;

use proc_macro2::{Delimiter, Group, Literal, Punct, Spacing, TokenStream, TokenTree};
use quote::quote;

/// The widest line the generated source should have.
const WIDTH: usize = 100;

/// The name of the placeholder macro; no sanitized identifier from a description starts with `__`.
const PLACEHOLDER: &str = "__drivegen_text!(";

/// A macro invocation waiting for its layout: the macro's path, its clauses (separated by `;`),
/// each a list of parts (separated by `,`).
struct Call {
    path: &'static str,
    clauses: Vec<Vec<String>>,
    /// Whether each clause ends in `;` when the call is laid out one clause per line.
    terminated: bool,
    /// Items already printed, laid out as the body of `path! { .. }` instead of the clauses.
    block: Option<String>,
}

thread_local! {
    static CALLS: RefCell<Vec<Call>> = const { RefCell::new(Vec::new()) };
}

/// Forgets the calls of an earlier generation (one generation per thread at a time).
pub(crate) fn reset() {
    CALLS.with(|calls| calls.borrow_mut().clear());
}

/// A placeholder item for `path!(body)`, where `body` is a list of `;`-separated clauses.
pub(crate) fn clauses_call(path: &'static str, body: TokenStream) -> TokenStream {
    placeholder(Call {
        path,
        clauses: split(body),
        terminated: true,
        block: None,
    })
}

/// A placeholder item for `path!(body)`, where `body` is one `,`-separated list.
pub(crate) fn list_call(path: &'static str, body: TokenStream) -> TokenStream {
    placeholder(Call {
        path,
        clauses: vec![split(body).concat()],
        terminated: false,
        block: None,
    })
}

/// A placeholder item for `path! { items }`, the items printed as prettyplease prints a file
/// (it prints a macro's body as one run of tokens), one level in.
pub(crate) fn block_call(path: &'static str, items: TokenStream) -> TokenStream {
    let file: syn::File = syn::parse2(items).expect("the emitter produces valid items");
    placeholder(Call {
        path,
        clauses: Vec::new(),
        terminated: false,
        block: Some(prettyplease::unparse(&file)),
    })
}

fn placeholder(call: Call) -> TokenStream {
    let index = CALLS.with(|calls| {
        let mut calls = calls.borrow_mut();
        calls.push(call);
        calls.len() - 1
    });
    let index = Literal::usize_unsuffixed(index);
    quote! { __drivegen_text!(#index); }
}

/// The printed source with every placeholder replaced by its call and every long doc line
/// wrapped.
pub(crate) fn finish(printed: &str) -> String {
    let calls: Vec<Call> = CALLS.with(|calls| std::mem::take(&mut *calls.borrow_mut()));
    let mut out = String::with_capacity(printed.len() + printed.len() / 8);
    render(printed, &calls, &mut out);
    out
}

/// [`finish`] of `printed` into `out`, with the calls of its placeholders.
fn render(printed: &str, calls: &[Call], out: &mut String) {
    let mut in_fence = false;
    for line in printed.lines() {
        let trimmed = line.trim_start();
        let indent = &line[..line.len() - trimmed.len()];
        match trimmed.strip_prefix(PLACEHOLDER).and_then(|rest| {
            let index: usize = rest.strip_suffix(");")?.parse().ok()?;
            calls.get(index)
        }) {
            Some(Call {
                path,
                block: Some(block),
                ..
            }) => {
                let _ = writeln!(out, "{indent}{path}! {{");
                let inner: String = block
                    .lines()
                    .map(|line| match line {
                        "" => "\n".to_owned(),
                        line => format!("{indent}    {line}\n"),
                    })
                    .collect();
                render(&inner, calls, out);
                let _ = writeln!(out, "{indent}}}");
            }
            Some(call) => lay_out(call, indent, out),
            None => match trimmed.strip_prefix("///") {
                Some(text) => {
                    let text = text.strip_prefix(' ').unwrap_or(text);
                    if text.starts_with("```") {
                        in_fence = !in_fence;
                    }
                    doc_line(indent, text, in_fence, out);
                }
                None => {
                    in_fence = false;
                    out.push_str(line);
                    out.push('\n');
                }
            },
        }
    }
}

/// One call at `indent`: on one line when it fits, otherwise one clause per line with long
/// clauses broken after a comma.
fn lay_out(call: &Call, indent: &str, out: &mut String) {
    let body: Vec<String> = call.clauses.iter().map(|c| c.join(", ")).collect();
    let one_line = format!("{indent}{}!({});", call.path, body.join("; "));
    if one_line.chars().count() <= WIDTH {
        out.push_str(&one_line);
        out.push('\n');
        return;
    }
    let _ = writeln!(out, "{indent}{}!(", call.path);
    let inner = format!("{indent}    ");
    for clause in &call.clauses {
        fill(clause, &inner, call.terminated, out);
    }
    let _ = writeln!(out, "{indent});");
}

/// The parts of one clause as full lines of `parts` joined by `, `, continued 4 columns further
/// in. A part too long for a line of its own is broken before its `=>`.
fn fill(parts: &[String], indent: &str, terminated: bool, out: &mut String) {
    let mut pieces: Vec<String> = Vec::new();
    for (i, part) in parts.iter().enumerate() {
        let tail = match (i + 1 == parts.len(), terminated) {
            (false, _) => ",",
            (true, true) => ";",
            (true, false) => "",
        };
        let too_long = indent.len() + part.chars().count() + 1 > WIDTH;
        match part.split_once(" => ").filter(|_| too_long) {
            Some((head, value)) => {
                pieces.push(head.to_owned());
                pieces.push(format!("=> {value}{tail}"));
            }
            None => pieces.push(format!("{part}{tail}")),
        }
    }
    let mut line = indent.to_owned();
    let start = line.len();
    for piece in pieces {
        if line.len() > start && line.chars().count() + 1 + piece.chars().count() > WIDTH {
            out.push_str(&line);
            out.push('\n');
            line = format!("{indent}    ");
        } else if line.len() > start {
            line.push(' ');
        }
        line.push_str(&piece);
    }
    out.push_str(&line);
    out.push('\n');
}

/// A doc line, wrapped at [`WIDTH`] between words. Table rows and code blocks are kept whole (a
/// row cannot continue on the next line), and no continuation starts with what Markdown would
/// read as a list item, heading, quote or table.
fn doc_line(indent: &str, text: &str, in_fence: bool, out: &mut String) {
    let room = WIDTH.saturating_sub(indent.len() + 4).max(40);
    if text.chars().count() <= room || in_fence || text.starts_with('|') {
        push_doc(indent, text, out);
        return;
    }
    let words: Vec<&str> = text.split(' ').filter(|w| !w.is_empty()).collect();
    let mut start = 0;
    while start < words.len() {
        let mut end = start + 1;
        let mut len = words[start].chars().count();
        while end < words.len() && len + 1 + words[end].chars().count() <= room {
            len += 1 + words[end].chars().count();
            end += 1;
        }
        // Move words to the next line until it starts safely (never below one word a line).
        while end < words.len() && end > start + 1 && starts_block(words[end]) {
            end -= 1;
        }
        push_doc(indent, &words[start..end].join(" "), out);
        start = end;
    }
}

fn push_doc(indent: &str, text: &str, out: &mut String) {
    out.push_str(indent);
    out.push_str("///");
    if !text.is_empty() {
        out.push(' ');
        out.push_str(text);
    }
    out.push('\n');
}

/// Whether a line starting with `word` would open a Markdown block instead of continuing the
/// paragraph.
fn starts_block(word: &str) -> bool {
    let ordered = word
        .strip_suffix(['.', ')'])
        .is_some_and(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()));
    ordered
        || matches!(word, "-" | "+" | "*")
        || word.starts_with(['#', '>', '|', '='])
        || word.bytes().all(|b| b == b'-')
}

/// The tokens of a macro body as text, split into `;`-separated clauses of `,`-separated parts.
fn split(body: TokenStream) -> Vec<Vec<String>> {
    let mut clauses = vec![Vec::new()];
    let mut part = Printer::default();
    for token in body {
        match &token {
            TokenTree::Punct(p) if p.as_char() == ';' => {
                let clause = clauses.last_mut().expect("never empty");
                clause.push(std::mem::take(&mut part).text);
                clauses.push(Vec::new());
            }
            TokenTree::Punct(p) if p.as_char() == ',' => {
                let clause = clauses.last_mut().expect("never empty");
                clause.push(std::mem::take(&mut part).text);
            }
            _ => part.token(token),
        }
    }
    let clause = clauses.last_mut().expect("never empty");
    if !part.text.is_empty() {
        clause.push(part.text);
    }
    clauses.retain(|c| !c.is_empty());
    clauses
}

/// Prints tokens with the spacing rustfmt would give them: paths and groups tight, operators
/// spaced, a minus sign after an operator or opening bracket as a sign.
#[derive(Default)]
struct Printer {
    text: String,
    /// The last token printed, for spacing: `None` at the start of a part or group.
    last: Option<Last>,
}

#[derive(Clone, Copy, PartialEq)]
enum Last {
    Word,
    /// A punctuation character; `joint` when the next one belongs to the same operator.
    Punct(char, bool),
    /// A unary minus: the literal follows it without a space.
    Sign,
    Group,
}

impl Printer {
    fn token(&mut self, token: TokenTree) {
        match token {
            TokenTree::Group(group) => self.group(&group),
            TokenTree::Punct(p) => self.punct(&p),
            word => self.word(&word),
        }
    }

    /// `(...)` or `[...]` tight against a name before it (`range(0, 10)`), its commas spaced.
    fn group(&mut self, group: &Group) {
        let (open, close) = match group.delimiter() {
            Delimiter::Parenthesis => ("(", ")"),
            Delimiter::Bracket => ("[", "]"),
            Delimiter::Brace => ("{", "}"),
            Delimiter::None => ("", ""),
        };
        if !matches!(
            self.last,
            None | Some(Last::Word | Last::Sign | Last::Punct(':', _))
        ) {
            self.text.push(' ');
        }
        self.text.push_str(open);
        let mut inner = Printer::default();
        for token in group.stream() {
            match &token {
                TokenTree::Punct(p) if p.as_char() == ',' => {
                    inner.text.push_str(", ");
                    inner.last = None;
                }
                _ => inner.token(token),
            }
        }
        self.text.push_str(inner.text.trim_end());
        self.text.push_str(close);
        self.last = Some(Last::Group);
    }

    /// Operators spaced (`=>`, `/`, `=`), `::`, `:` and generics' `<>` tight, a leading `-` a sign.
    fn punct(&mut self, p: &Punct) {
        let c = p.as_char();
        let joint = p.spacing() == Spacing::Joint;
        let space = match (self.last, c) {
            (None, _) | (Some(Last::Punct(_, true)), _) => false,
            (_, ':') if joint => !matches!(self.last, Some(Last::Word)),
            (_, ':') => false,
            (Some(Last::Word | Last::Group), '<' | '>') => false,
            _ => true,
        };
        if space {
            self.text.push(' ');
        }
        self.text.push(c);
        let sign = c == '-' && !matches!(self.last, Some(Last::Word | Last::Group));
        self.last = Some(if sign {
            Last::Sign
        } else {
            Last::Punct(c, joint)
        });
    }

    /// A name or literal, spaced from what came before unless that was a sign, `::` or `<`.
    fn word(&mut self, token: &TokenTree) {
        let space = match self.last {
            None | Some(Last::Sign) | Some(Last::Punct('<', _)) | Some(Last::Punct(_, true)) => {
                false
            }
            Some(Last::Punct(':', _)) => !self.text.ends_with("::"),
            _ => true,
        };
        if space {
            self.text.push(' ');
        }
        let _ = write!(self.text, "{token}");
        self.last = Some(Last::Word);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn printed(tokens: TokenStream) -> Vec<Vec<String>> {
        split(tokens)
    }

    #[test]
    fn macro_bodies_print_with_hand_written_spacing() {
        let body = quote! {
            BusDcLink = "bus_dc_link": u16 => ::drivebus::units::Volts, InUnit,
            scale = 1 / 100, offset = -40 / 1, range(-5, 20);
            read modbus(input 0x0064) runtime;
            write modbus[(holding 0x0010, 2 words, LowFirst), _];
            read canopen(0x6041 sub 0, 2 bytes)
        };
        assert_eq!(
            printed(body),
            [
                vec![
                    "BusDcLink = \"bus_dc_link\": u16 => ::drivebus::units::Volts",
                    "InUnit",
                    "scale = 1 / 100",
                    "offset = -40 / 1",
                    "range(-5, 20)",
                ],
                vec!["read modbus(input 0x0064) runtime"],
                vec!["write modbus[(holding 0x0010, 2 words, LowFirst), _]"],
                vec!["read canopen(0x6041 sub 0, 2 bytes)"],
            ]
        );
        assert_eq!(
            printed(quote! { X: ::drivebus::value::Text<8> => types::Mode, Plain }),
            [vec![
                "X: ::drivebus::value::Text<8> => types::Mode",
                "Plain"
            ]]
        );
    }

    #[test]
    fn a_call_that_does_not_fit_takes_one_line_per_clause() {
        reset();
        let long = "a".repeat(60);
        let ident = crate::emit::rust::ident(&long);
        let item = clauses_call(
            "::m::call",
            quote! { #ident = 1, two = 2; read x(1); write y(2) },
        );
        assert_eq!(item.to_string().replace(' ', ""), "__drivegen_text!(0);");
        let text = finish("    __drivegen_text!(0);\n");
        assert_eq!(
            text,
            format!("    ::m::call!(\n        {long} = 1, two = 2;\n        read x(1);\n        write y(2);\n    );\n")
        );
    }

    #[test]
    fn long_doc_lines_wrap_between_words_and_never_start_a_block() {
        let text = format!("{} - item 1. ok | no", "word ".repeat(18).trim_end());
        let mut out = String::new();
        doc_line("    ", text.trim(), false, &mut out);
        for line in out.lines() {
            assert!(line.len() <= WIDTH, "{line}");
            let rest = line.trim_start().trim_start_matches("///").trim_start();
            assert!(!starts_block(rest.split(' ').next().unwrap()), "{out}");
        }
        let joined: Vec<&str> = out
            .lines()
            .map(|l| l.trim_start().trim_start_matches("/// "))
            .collect();
        assert_eq!(joined.join(" "), text.trim());
        let row = format!("| Source | {} |", "x ".repeat(60));
        let mut out = String::new();
        doc_line("", &row, false, &mut out);
        assert_eq!(out.lines().count(), 1, "a table row stays whole");
    }
}
