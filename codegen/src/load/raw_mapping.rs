//! `[[pdo]]` and `[[srdo]]` tables as written: see `docs/description-format.md`. The two tables
//! keep their own keys; [`RawMapping`] is what they write alike, for the one lowering.

use serde::Deserialize;
use toml::Spanned;

use super::raw::RawCitation;

/// `[[pdo]]`: a PDO mapping.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawPdoMapping {
    pub name: Spanned<String>,
    pub doc: Option<String>,
    pub direction: Spanned<String>,
    pub number: Spanned<i64>,
    pub cob_id: Option<Spanned<RawCobId>>,
    pub enabled: Option<Spanned<bool>>,
    pub transmission_type: Option<Spanned<i64>>,
    pub inhibit_time: Option<Spanned<i64>>,
    pub event_timer: Option<Spanned<i64>>,
    pub entries: Spanned<Vec<String>>,
    pub source: Option<Spanned<RawCitation>>,
}

/// A PDO COB-ID: a number, or a text such as `"$NODEID+0x180"`.
#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub enum RawCobId {
    Number(i64),
    Text(String),
}

/// `[[srdo]]`: one safety-related data object (CANopen Safety, EN 50325-5), its default
/// communication parameters and mapping.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawSrdo {
    pub name: Spanned<String>,
    pub doc: Option<String>,
    pub number: Spanned<i64>,
    pub direction: Spanned<String>,
    pub enabled: Option<bool>,
    pub sct_ms: Spanned<i64>,
    pub srvt_ms: Spanned<i64>,
    pub transmission_type: Option<Spanned<i64>>,
    pub cob_ids: Spanned<Vec<RawSrdoCobId>>,
    pub entries: Spanned<Vec<String>>,
    pub source: Option<Spanned<RawCitation>>,
    pub erratum: Option<String>,
}

/// An SRDO COB-ID: a number, or `{ base, node_id_factor }` for `base + factor × node-ID`.
#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub enum RawSrdoCobId {
    Number(i64),
    NodeRelative(RawNodeRelativeCobId),
}

/// `{ base, node_id_factor }`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawNodeRelativeCobId {
    pub base: i64,
    pub node_id_factor: i64,
}

/// The keys `[[pdo]]` and `[[srdo]]` share.
pub struct RawMapping<'a> {
    pub name: &'a Spanned<String>,
    pub doc: &'a Option<String>,
    pub direction: &'a Spanned<String>,
    pub enabled: bool,
    pub transmission_type: Option<&'a Spanned<i64>>,
    pub entries: &'a Spanned<Vec<String>>,
    pub source: Option<&'a Spanned<RawCitation>>,
}

impl RawPdoMapping {
    /// The shared keys; a PDO is enabled unless it says otherwise.
    pub fn shared(&self) -> RawMapping<'_> {
        RawMapping {
            name: &self.name,
            doc: &self.doc,
            direction: &self.direction,
            enabled: self.enabled.as_ref().is_none_or(|e| *e.get_ref()),
            transmission_type: self.transmission_type.as_ref(),
            entries: &self.entries,
            source: self.source.as_ref(),
        }
    }
}

impl RawSrdo {
    /// The shared keys; an SRDO is enabled unless it says otherwise.
    pub fn shared(&self) -> RawMapping<'_> {
        RawMapping {
            name: &self.name,
            doc: &self.doc,
            direction: &self.direction,
            enabled: self.enabled.unwrap_or(true),
            transmission_type: self.transmission_type.as_ref(),
            entries: &self.entries,
            source: self.source.as_ref(),
        }
    }
}
