//! What goes over MQTT: a value as JSON (`{"value": 49.5, "unit": "V", "raw": 4950, "time":
//! "..."}`, enums and flags by name with their raw value), and a set message (`{"value": 1500}`
//! in engineering units, `{"value": "velocity"}` by name, or `{"raw": 4950}`) as the text
//! `drivegen write` takes.

use std::time::SystemTime;

use drivebus::interpret::Shown;
use drivegen::ir::Parameter;

use crate::codec;

/// A value's JSON, read at `time`.
pub fn value(parameter: &Parameter, shown: &Shown, time: SystemTime) -> serde_json::Value {
    serde_json::json!({
        "value": codec::value_json(&shown.value),
        "unit": parameter.unit,
        "raw": codec::raw_json(&shown.raw),
        "time": humantime::format_rfc3339_millis(time).to_string(),
    })
}

/// Whether two value payloads carry the same value (their times aside).
pub fn same_value(a: &serde_json::Value, b: &serde_json::Value) -> bool {
    a.get("value") == b.get("value") && a.get("raw") == b.get("raw")
}

/// A set message as the value text `drivegen write` parses, or why it is not one.
pub fn set_text(message: &[u8]) -> Result<String, String> {
    let json: serde_json::Value =
        serde_json::from_slice(message).map_err(|e| format!("the message is not JSON: {e}"))?;
    let object = json
        .as_object()
        .ok_or("expected an object: {\"value\": ...} or {\"raw\": ...}")?;
    match (object.get("value"), object.get("raw"), object.len()) {
        (Some(value), None, 1) => match value {
            serde_json::Value::Number(n) => Ok(n.to_string()),
            serde_json::Value::String(s) => Ok(s.clone()),
            other => Err(format!("`value` must be a number or a name, not {other}")),
        },
        (None, Some(raw), 1) => match raw
            .as_i64()
            .map(i128::from)
            .or(raw.as_u64().map(i128::from))
        {
            Some(int) => Ok(format!("raw:{int}")),
            None => Err(format!("`raw` must be an integer, not {raw}")),
        },
        _ => Err("expected exactly one of `value` or `raw`".into()),
    }
}

/// The answer to a set message, on `.../set/result`.
pub fn set_result(
    parameter: Option<&Parameter>,
    outcome: &Result<Shown, String>,
) -> serde_json::Value {
    match (outcome, parameter) {
        (Ok(shown), Some(parameter)) => serde_json::json!({
            "ok": true,
            "value": codec::value_json(&shown.value),
            "unit": parameter.unit,
            "raw": codec::raw_json(&shown.raw),
        }),
        (Ok(_), None) => serde_json::json!({ "ok": true }),
        (Err(why), _) => serde_json::json!({ "ok": false, "error": why }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn set_messages_become_the_text_write_takes() {
        assert_eq!(set_text(br#"{"value": 1500}"#).unwrap(), "1500");
        assert_eq!(set_text(br#"{"value": 49.5}"#).unwrap(), "49.5");
        assert_eq!(set_text(br#"{"value": "velocity"}"#).unwrap(), "velocity");
        assert_eq!(set_text(br#"{"raw": 4950}"#).unwrap(), "raw:4950");
        assert_eq!(set_text(br#"{"raw": -3}"#).unwrap(), "raw:-3");
    }

    #[test]
    fn anything_else_is_refused_with_the_reason() {
        for (message, reason) in [
            (&b"1500"[..], "expected an object"),
            (b"{value: 1}", "not JSON"),
            (br#"{"value": 1, "raw": 1}"#, "exactly one"),
            (br#"{"speed": 1}"#, "exactly one"),
            (br#"{"value": [1]}"#, "number or a name"),
            (br#"{"raw": 1.5}"#, "integer"),
        ] {
            let why = set_text(message).expect_err("refused");
            assert!(why.contains(reason), "{why}");
        }
    }

    #[test]
    fn payloads_compare_by_value_and_raw_not_time() {
        let a = serde_json::json!({"value": 1, "raw": 10, "time": "t1"});
        let b = serde_json::json!({"value": 1, "raw": 10, "time": "t2"});
        let c = serde_json::json!({"value": 2, "raw": 20, "time": "t1"});
        assert!(same_value(&a, &b));
        assert!(!same_value(&a, &c));
    }
}
