//! The units the descriptions use, as OPC UA `EUInformation` (OPC 10000-8 §5.6.3): each symbol
//! with its UN/CEFACT common code from UNECE Recommendation 20 (rev. 17, Annex I/II), and the
//! code packed into the `UnitId` as the specification says. Units without a code (`inc`,
//! `rpm/s`, `rps/s`) get `UnitId` -1 with their symbol as the display name, as §5.6.3 allows.

use opcua::types::{EUInformation, LocalizedText, UAString};

/// The namespace of UNECE unit ids.
const UNECE: &str = "http://www.opcfoundation.org/UA/units/un/cefact";

/// Symbol as written in the descriptions, UNECE Rec. 20 common code, the unit's name.
const UNITS: &[(&str, &str, &str)] = &[
    ("%", "P1", "percent"),
    ("‰", "NX", "part per thousand"),
    ("A", "AMP", "ampere"),
    // Arms: a current in amperes (r.m.s.); Rec. 20 has no code for the kind of value.
    ("Arms", "AMP", "ampere (r.m.s.)"),
    ("mA", "4K", "milliampere"),
    ("V", "VLT", "volt"),
    ("mV", "2Z", "millivolt"),
    ("W", "WTT", "watt"),
    ("Ω", "OHM", "ohm"),
    ("Hz", "HTZ", "hertz"),
    ("s", "SEC", "second [unit of time]"),
    ("ms", "C26", "millisecond"),
    ("rpm", "RPM", "revolutions per minute"),
    ("°C", "CEL", "degree Celsius"),
];

/// The `EUInformation` of a unit symbol.
pub fn eu_information(symbol: &str) -> EUInformation {
    let known = UNITS.iter().find(|(s, _, _)| *s == symbol);
    let (unit_id, description) = match known {
        Some((_, code, name)) => (unit_id(code), *name),
        None => (-1, symbol),
    };
    EUInformation {
        namespace_uri: UAString::from(UNECE),
        unit_id,
        display_name: LocalizedText::new("", symbol),
        description: LocalizedText::new("en", description),
    }
}

/// A common code packed as OPC 10000-8 §5.6.3 says: each of its (up to three) ASCII characters
/// shifted in from the right.
fn unit_id(code: &str) -> i32 {
    code.bytes().fold(0, |id, c| (id << 8) | i32::from(c))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_pack_as_the_specification_says() {
        // The examples of OPC 10000-8 §5.6.3 / UNECE_to_OPCUA.csv: CEL and C26.
        assert_eq!(unit_id("CEL"), 4408652);
        assert_eq!(unit_id("C26"), 4403766);
        assert_eq!(unit_id("P1"), 20529);
        assert_eq!(eu_information("°C").unit_id, 4408652);
        assert_eq!(eu_information("inc").unit_id, -1);
        assert_eq!(eu_information("inc").display_name.text.as_ref(), "inc");
    }
}
