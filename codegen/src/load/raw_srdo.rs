//! `[[srdo]]` tables as written (CANopen Safety, EN 50325-5): see `docs/description-format.md`.

use serde::Deserialize;
use toml::Spanned;

use super::raw::RawCitation;

/// `[[srdo]]`: one safety-related data object, its default communication parameters and mapping.
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
