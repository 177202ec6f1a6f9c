//! The JSON of mappings: `pdos` and `srdos`, each left out when empty, each mapping with the keys
//! of its kind in the documented order (`docs/ir-json.md`). The IR keeps one list of one
//! concept; the schema, which only ever grows, keeps the two arrays it has always had.

use serde::ser::{SerializeMap, Serializer};
use serde::Serialize;

use super::{Citation, CobId, Direction, Mapping, MappingKind, SrdoCobId};

/// A `[[pdo]]` as JSON.
#[derive(Serialize)]
struct PdoJson<'a> {
    name: &'a str,
    doc: &'a Option<String>,
    direction: Direction,
    number: u16,
    cob_id: Option<CobId>,
    enabled: bool,
    transmission_type: Option<u8>,
    inhibit_time: Option<u16>,
    event_timer: Option<u16>,
    entries: &'a [String],
    source: &'a Option<Citation>,
}

/// A `[[srdo]]` as JSON.
#[derive(Serialize)]
struct SrdoJson<'a> {
    name: &'a str,
    doc: &'a Option<String>,
    number: u8,
    direction: Direction,
    enabled: bool,
    sct_ms: u16,
    srvt_ms: u16,
    transmission_type: Option<u8>,
    cob_ids: [SrdoCobId; 2],
    entries: &'a [String],
    source: &'a Option<Citation>,
    erratum: &'a Option<String>,
}

impl Serialize for Mapping {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match &self.kind {
            MappingKind::Pdo(p) => PdoJson {
                name: &self.name,
                doc: &self.doc,
                direction: self.direction,
                number: p.number,
                cob_id: p.cob_id,
                enabled: self.enabled,
                transmission_type: self.transmission_type,
                inhibit_time: p.inhibit_time,
                event_timer: p.event_timer,
                entries: &self.entries,
                source: &self.source,
            }
            .serialize(serializer),
            MappingKind::Srdo(s) => SrdoJson {
                name: &self.name,
                doc: &self.doc,
                number: s.number,
                direction: self.direction,
                enabled: self.enabled,
                sct_ms: s.sct_ms,
                srvt_ms: s.srvt_ms,
                transmission_type: self.transmission_type,
                cob_ids: s.cob_ids,
                entries: &self.entries,
                source: &self.source,
                erratum: &s.erratum,
            }
            .serialize(serializer),
        }
    }
}

/// `Device::mappings` as the keys `pdos` and `srdos` of the device object (flattened into it).
pub(super) fn by_kind<S: Serializer>(
    mappings: &[Mapping],
    serializer: S,
) -> Result<S::Ok, S::Error> {
    let pdos: Vec<&Mapping> = mappings.iter().filter(|m| m.pdo().is_some()).collect();
    let srdos: Vec<&Mapping> = mappings.iter().filter(|m| m.srdo().is_some()).collect();
    let mut map = serializer.serialize_map(None)?;
    for (key, list) in [("pdos", pdos), ("srdos", srdos)] {
        if !list.is_empty() {
            map.serialize_entry(key, &list)?;
        }
    }
    map.end()
}

#[cfg(test)]
mod tests {
    use crate::validate::test_support::device;

    const WORDS: &str = "[[parameter]]\nname = \"w\"\ntype = \"u8\"\ncanopen = { index = 0x6620, subindex = 1, pdo = \"tx\" }\nsource = { doc = \"m\", line = 1 }\n[[parameter]]\nname = \"w_inv\"\ntype = \"u8\"\ncanopen = { index = 0x6622, subindex = 1 }\nsource = { doc = \"m\", line = 2 }\n";

    const PDO: &str = "[[pdo]]\nname = \"tpdo1\"\ndirection = \"tx\"\nnumber = 1\ncob_id = \"$NODEID+0x180\"\nevent_timer = 100\nentries = [\"w\"]\nsource = { doc = \"m\", line = 3 }\n";

    const SRDO: &str = "[[srdo]]\nname = \"s\"\nnumber = 2\ndirection = \"rx\"\nsct_ms = 50\nsrvt_ms = 20\ncob_ids = [0x101, { base = 0x100, node_id_factor = 2 }]\nentries = [\"w\", \"w_inv\"]\nsource = { doc = \"m\", line = 4 }\nerratum = \"e\"\n";

    #[test]
    fn pdos_and_srdos_keep_their_keys_in_the_documented_order() {
        let json = serde_json::to_string(&device(&format!("{WORDS}{SRDO}{PDO}"))).unwrap();
        let pdos = r#""pdos":[{"name":"tpdo1","doc":null,"direction":"tx","number":1,"cob_id":{"value":384,"plus_node_id":true},"enabled":true,"transmission_type":null,"inhibit_time":null,"event_timer":100,"entries":["w"],"source":{"doc":"m","file":"manual.txt","section":null,"line":3,"example":null}}]"#;
        let srdos = r#""srdos":[{"name":"s","doc":null,"number":2,"direction":"rx","enabled":true,"sct_ms":50,"srvt_ms":20,"transmission_type":null,"cob_ids":[{"base":257,"node_id_factor":0},{"base":256,"node_id_factor":2}],"entries":["w","w_inv"],"source":{"doc":"m","file":"manual.txt","section":null,"line":4,"example":null},"erratum":"e"}]"#;
        assert!(json.ends_with(&format!(",{pdos},{srdos}}}")), "{json}");
    }

    #[test]
    fn no_mappings_leave_both_keys_out() {
        let json = serde_json::to_string(&device(WORDS)).unwrap();
        assert!(
            !json.contains("\"pdos\"") && !json.contains("\"srdos\""),
            "{json}"
        );
    }
}
