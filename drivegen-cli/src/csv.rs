//! CSV as `trace --csv` and `watch --csv` write it (RFC 4180): fields quoted only where needed.

/// A CSV field, quoted where it holds a comma, a quote or a line break.
pub fn field(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_owned()
    }
}

/// A CSV record of `fields`, without its line break.
pub fn record<S: AsRef<str>>(fields: &[S]) -> String {
    let fields: Vec<String> = fields.iter().map(|f| field(f.as_ref())).collect();
    fields.join(",")
}

#[cfg(test)]
mod tests {
    #[test]
    fn only_fields_that_need_it_are_quoted() {
        assert_eq!(
            super::record(&["a", "b,c", "say \"hi\"", "x\ny"]),
            "a,\"b,c\",\"say \"\"hi\"\"\",\"x\ny\""
        );
    }
}
