//! Exact numbers as written in descriptions: `10`, `-40`, `0.1`, `1/100`, `"1875/512"`.

/// Parses an unsigned or signed decimal (`12`, `-0.25`) into `numerator / denominator`.
pub fn parse_decimal(text: &str) -> Option<(i64, i64)> {
    let text = text.trim();
    let (negative, digits) = match text.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, text),
    };
    let (whole, fraction) = digits.split_once('.').unwrap_or((digits, ""));
    let all_digits = |s: &str| s.bytes().all(|b| b.is_ascii_digit());
    if whole.is_empty() || !all_digits(whole) || !all_digits(fraction) || fraction.len() > 18 {
        return None;
    }
    let denominator = 10i64.checked_pow(fraction.len() as u32)?;
    let numerator: i64 = format!("{whole}{fraction}").parse().ok()?;
    let (n, d) = reduce(numerator, denominator)?;
    Some((if negative { -n } else { n }, d))
}

/// Parses `a`, `a/b` with decimals allowed on both sides.
pub fn parse_ratio(text: &str) -> Option<(i64, i64)> {
    match text.split_once('/') {
        None => parse_decimal(text),
        Some((num, den)) => {
            let (a, b) = parse_decimal(num)?;
            let (c, d) = parse_decimal(den)?;
            reduce(a.checked_mul(d)?, b.checked_mul(c)?)
        }
    }
}

/// The exact value of a float as its shortest decimal representation (`0.1` → 1/10).
pub fn float_ratio(value: f64) -> Option<(i64, i64)> {
    if !value.is_finite() {
        return None;
    }
    let text = format!("{value}");
    parse_decimal(&text)
}

fn reduce(numerator: i64, denominator: i64) -> Option<(i64, i64)> {
    if denominator == 0 {
        return None;
    }
    let g = gcd(numerator.unsigned_abs(), denominator.unsigned_abs()).max(1) as i64;
    let sign = if denominator < 0 { -1 } else { 1 };
    Some((sign * numerator / g, sign * denominator / g))
}

fn gcd(a: u64, b: u64) -> u64 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_rationals_and_decimals_exactly() {
        assert_eq!(parse_ratio("1/100"), Some((1, 100)));
        assert_eq!(parse_ratio("0.1"), Some((1, 10)));
        assert_eq!(parse_ratio("-40"), Some((-40, 1)));
        assert_eq!(parse_ratio("1875/512"), Some((1875, 512)));
        assert_eq!(parse_ratio("2.5/0.5"), Some((5, 1)));
        assert_eq!(float_ratio(0.01), Some((1, 100)));
    }

    #[test]
    fn refuses_garbage_and_zero_denominators() {
        for bad in ["", "1/0", "abc", "1/2/3", "0x10", "1e3", "--1", ".5"] {
            assert_eq!(parse_ratio(bad), None, "{bad}");
        }
    }
}
