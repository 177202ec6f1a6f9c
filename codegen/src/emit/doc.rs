//! Documentation text from descriptions, made safe for rustdoc.
//!
//! Doc strings are emitted as `#[doc = "..."]` literals, so quotes cannot escape them; what remains
//! is Markdown: a fenced or indented block would become a doctest that runs description text as
//! code. Backticks, angle brackets and leading indentation are therefore neutralised.

/// The first line of an item's escaped doc text, or its name when it has none: the one-line
/// summary of an accessor.
pub fn summary(doc: Option<&str>, name: &str) -> String {
    escape(doc.unwrap_or(name))
        .lines()
        .next()
        .unwrap_or_default()
        .to_owned()
}

/// Escapes description text for a rustdoc comment.
pub fn escape(text: &str) -> String {
    text.lines()
        .map(|line| {
            line.trim_start()
                .replace('\\', "\\\\")
                .replace('`', "\\`")
                .replace('<', "&lt;")
                .replace('>', "&gt;")
                .replace('[', "\\[")
                .replace(']', "\\]")
                .replace('~', "\\~")
                .replace('|', "\\|")
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn code_fences_and_indented_blocks_are_neutralised() {
        assert_eq!(
            escape("```\nfn main(){}\n```"),
            "\\`\\`\\`\nfn main(){}\n\\`\\`\\`"
        );
        assert_eq!(escape("a\n\n    let x = 1;"), "a\n\nlet x = 1;");
        assert_eq!(escape("<script>"), "&lt;script&gt;");
    }
}
