//! Values as the CLI prints them for scripts: the run-time interpreter's shown values
//! (`drivebus::interpret::show`) as JSON.

use drivebus::interpret::{Engineering, Raw, RawValue};

/// The raw value as JSON: an integer exactly, the bytes of text as an array.
pub fn raw_json(raw: &Raw) -> serde_json::Value {
    match raw {
        Raw::Bytes(bytes) => serde_json::Value::from(bytes.clone()),
        Raw::Number(RawValue::Int(int)) => exact_json(*int),
        Raw::Number(RawValue::Float(float)) => serde_json::Value::from(*float),
        Raw::Undecodable => serde_json::Value::Null,
    }
}

/// The engineering value as JSON: a number, or the text of names and strings.
pub fn value_json(value: &Engineering) -> serde_json::Value {
    match value {
        Engineering::Int(int) => exact_json(*int),
        Engineering::Float(float) => serde_json::Value::from(*float),
        Engineering::Text(text) => serde_json::Value::from(text.as_str()),
        Engineering::Unknown => serde_json::Value::Null,
    }
}

/// An integer as a JSON number, exact for every 64-bit value (JSON readers that parse numbers
/// as doubles may still round it; those that keep integers get it whole).
fn exact_json(int: i128) -> serde_json::Value {
    match (i64::try_from(int), u64::try_from(int)) {
        (Ok(i), _) => serde_json::Value::from(i),
        (_, Ok(u)) => serde_json::Value::from(u),
        _ => serde_json::Value::from(int as f64),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wide_integers_stay_exact_in_json() {
        let wide = i128::from(u64::MAX - 5);
        assert_eq!(
            raw_json(&Raw::Number(RawValue::Int(wide))),
            serde_json::json!(u64::MAX - 5)
        );
        assert_eq!(value_json(&Engineering::Int(-3)), serde_json::json!(-3));
        assert_eq!(
            raw_json(&Raw::Bytes(b"ab".to_vec())),
            serde_json::json!([97, 98])
        );
    }
}
