//! The syntax of a sub-index run: `"1..=8"` (inclusive) or `"0x01..=0x08"`; also `"1..9"`
//! (exclusive end, as in Rust). Both ends are sub-indices 1..=254, the first not after the last.

/// The first and last sub-index of `text`, or why it is not a run.
pub fn parse(text: &str) -> Result<(u8, u8), String> {
    let (first, last, inclusive) = match text.split_once("..=") {
        Some((a, b)) => (a, b, true),
        None => match text.split_once("..") {
            Some((a, b)) => (a, b, false),
            None => return Err(format!("`{text}` is not a sub-index run")),
        },
    };
    let first = number(first)?;
    let last = number(last)? - i64::from(!inclusive);
    if !(1..=254).contains(&first) || !(1..=254).contains(&last) {
        return Err(format!(
            "`{text}`: a run lies within sub-indices 1..=254 (sub-index 0 is the entry count)"
        ));
    }
    if first > last {
        return Err(format!("`{text}`: the run is empty"));
    }
    // Both lie in 1..=254, checked above.
    Ok((first as u8, last as u8))
}

fn number(text: &str) -> Result<i64, String> {
    let text = text.trim();
    let parsed = match text.strip_prefix("0x").or_else(|| text.strip_prefix("0X")) {
        Some(hex) => i64::from_str_radix(hex, 16),
        None => text.parse(),
    };
    parsed.map_err(|_| format!("`{text}` is not a sub-index"))
}

#[cfg(test)]
mod tests {
    use super::parse;

    #[test]
    fn runs_are_read_inclusive_or_exclusive_in_decimal_or_hex() {
        assert_eq!(parse("1..=8"), Ok((1, 8)));
        assert_eq!(parse("0x01..=0x0A"), Ok((1, 10)));
        assert_eq!(parse("1..9"), Ok((1, 8)));
        assert_eq!(parse(" 2 ..= 6 "), Ok((2, 6)));
        assert_eq!(parse("1..=254"), Ok((1, 254)));
    }

    #[test]
    fn malformed_empty_or_out_of_bounds_runs_are_refused() {
        for bad in ["8", "1-8", "a..=3", "0..=3", "1..=255", "5..=4", "3..3", ""] {
            assert!(parse(bad).is_err(), "{bad:?} was accepted");
        }
    }
}
