//! The manuals' notation brought to the comparator's forms, so a table can be typed as the manual
//! prints it: `0x` hex numbers as decimal, fractions in lowest terms (a manual's 10/4095 V is
//! 2/819), enumeration and allowed values ascending, Modbus addresses in lower-case hex. Only the
//! notation changes, never a value; what is not an integer (a float range, `-` for "none",
//! `$NODEID+N`) is left as written.

/// `value` of `key` in the comparator's form.
pub fn normalised(key: &str, value: &str) -> String {
    match key {
        "modbus" => value.to_lowercase(),
        "scale" => reduced(value).unwrap_or_else(|| value.to_owned()),
        "values" | "allowed" => ascending(value).unwrap_or_else(|| value.to_owned()),
        "range" => range(value).unwrap_or_else(|| value.to_owned()),
        "default" => integer(value).map_or_else(|| value.to_owned(), |n| n.to_string()),
        _ => value.to_owned(),
    }
}

/// A whole number as the manuals print it: decimal or `0x` hex, maybe negative.
fn integer(text: &str) -> Option<i128> {
    let (negative, digits) = match text.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, text),
    };
    let magnitude = match digits
        .strip_prefix("0x")
        .or_else(|| digits.strip_prefix("0X"))
    {
        Some(hex) => i128::from_str_radix(hex, 16).ok()?,
        None => digits.parse().ok()?,
    };
    Some(if negative { -magnitude } else { magnitude })
}

/// `N/D` in lowest terms; `None` when either side is not a whole number or D is zero.
fn reduced(scale: &str) -> Option<String> {
    let (numerator, denominator) = scale.split_once('/')?;
    let (n, d) = (integer(numerator)?, integer(denominator)?);
    let divisor = gcd(n.abs(), d.abs());
    if divisor == 0 {
        return None;
    }
    Some(match d / divisor {
        1 => (n / divisor).to_string(),
        den => format!("{}/{den}", n / divisor),
    })
}

fn gcd(mut a: i128, mut b: i128) -> i128 {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

/// `,`-joined whole numbers in ascending order; `None` if one is not a whole number.
fn ascending(list: &str) -> Option<String> {
    let mut numbers = list.split(',').map(integer).collect::<Option<Vec<_>>>()?;
    numbers.sort_unstable();
    Some(
        numbers
            .iter()
            .map(ToString::to_string)
            .collect::<Vec<_>>()
            .join(","),
    )
}

/// `MIN..MAX` with both ends as decimal whole numbers.
fn range(text: &str) -> Option<String> {
    let (min, max) = text.split_once("..")?;
    Some(format!("{}..{}", integer(min)?, integer(max)?))
}

#[cfg(test)]
mod tests {
    use super::normalised;

    #[test]
    fn manual_notation_becomes_the_comparators() {
        assert_eq!(normalised("scale", "10/4095"), "2/819");
        assert_eq!(normalised("scale", "100/100"), "1");
        assert_eq!(normalised("range", "0x0000..0xFFFF"), "0..65535");
        assert_eq!(normalised("range", "-0x10..16"), "-16..16");
        assert_eq!(normalised("values", "3,0x1,-2"), "-2,1,3");
        assert_eq!(normalised("default", "0x64"), "100");
        assert_eq!(
            normalised("modbus", "holding:0x00A5:rw"),
            "holding:0x00a5:rw"
        );
    }

    #[test]
    fn what_is_not_a_whole_number_is_left_as_written() {
        assert_eq!(normalised("range", "-0.5..1.5"), "-0.5..1.5");
        assert_eq!(normalised("range", "-"), "-");
        assert_eq!(normalised("default", "$NODEID+0x180"), "$NODEID+0x180");
        assert_eq!(normalised("scale", "1/10+5"), "1/10+5");
        assert_eq!(normalised("scale", "runtime"), "runtime");
        assert_eq!(normalised("scale", "1/0"), "1/0");
        assert_eq!(normalised("type", "0x10"), "0x10");
    }
}
