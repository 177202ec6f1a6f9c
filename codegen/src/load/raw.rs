//! The description file as written: serde structures that keep the source span of every value.
//!
//! Nothing here is interpreted; [`super::lower`] turns these into the IR and reports what is wrong.

use serde::Deserialize;
use toml::Spanned;

/// One TOML file of a description.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawFile {
    pub format: Spanned<i64>,
    /// An EDS this file is an overlay of (root file only).
    pub eds: Option<Spanned<String>>,
    #[serde(default)]
    pub include: Vec<Spanned<RawInclude>>,
    pub device: Option<RawDevice>,
    pub profile: Option<RawProfile>,
    #[serde(default)]
    pub source: Vec<RawSource>,
    pub modbus: Option<RawModbusCaps>,
    pub canopen: Option<RawCanOpenCaps>,
    pub identity: Option<super::raw_identity::RawIdentity>,
    pub lock: Option<super::raw_lock::RawLock>,
    #[serde(default)]
    pub unlock: Vec<super::raw_lock::RawUnlock>,
    pub watchdog: Option<super::raw_lock::RawWatchdog>,
    #[serde(default)]
    pub variant: Vec<RawVariant>,
    #[serde(default, rename = "enum")]
    pub enums: Vec<RawEnum>,
    #[serde(default)]
    pub flags: Vec<RawFlags>,
    #[serde(default)]
    pub record: Vec<RawRecord>,
    #[serde(default)]
    pub parameter: Vec<RawParameter>,
    pub cia402: Option<Spanned<RawCia402>>,
    pub state_machine: Option<Spanned<RawStateMachine>>,
    #[serde(default)]
    pub state: Vec<Spanned<RawState>>,
    #[serde(default)]
    pub transition: Vec<Spanned<RawTransition>>,
    #[serde(default)]
    pub ramp: Vec<super::raw_ramp::RawRamp>,
    #[serde(default)]
    pub pdo: Vec<super::raw_mapping::RawPdoMapping>,
    #[serde(default)]
    pub srdo: Vec<super::raw_mapping::RawSrdo>,
    #[serde(default)]
    pub refine: Vec<RawRefine>,
    #[serde(default)]
    pub constant: Vec<RawConstant>,
    #[serde(default)]
    pub model: Vec<RawModel>,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(untagged)]
pub enum RawInclude {
    Path(String),
    Table(RawIncludeTable),
}

/// `{ path, only }`: a struct of its own so a misspelt key is an error, not a silent full include.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawIncludeTable {
    pub path: String,
    pub only: Option<RawOnly>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawDevice {
    pub name: Spanned<String>,
    pub handle: Spanned<String>,
    pub vendor: Option<String>,
    pub firmware: Option<String>,
    pub doc: Option<String>,
    pub source: Option<Spanned<RawCitation>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawProfile {
    pub name: Spanned<String>,
    pub doc: Option<String>,
    pub source: Option<Spanned<RawCitation>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawSource {
    pub id: Spanned<String>,
    pub file: String,
    pub title: String,
    /// A published standard (CiA 402), cited by section: its citations need no line.
    #[serde(default)]
    pub standard: bool,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawCitation {
    pub doc: Spanned<String>,
    pub section: Option<String>,
    pub line: Option<Spanned<i64>>,
    pub example: Option<String>,
    /// The manual's own name of the register or object (`"BUS DC LINK"`, `"C01"`).
    pub name: Option<String>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawModbusCaps {
    pub max_read_registers: Option<Spanned<i64>>,
    pub max_write_registers: Option<Spanned<i64>>,
    pub functions: Option<Spanned<Vec<i64>>>,
    pub broadcast: Option<bool>,
    pub read_gaps: Option<bool>,
    pub word_order: Option<Spanned<String>>,
    pub illegal_address_exception: Option<Spanned<i64>>,
    pub illegal_value_exception: Option<Spanned<i64>>,
    pub exception_functions: Option<Spanned<Vec<RawExceptionFunction>>>,
    #[serde(default)]
    pub read_blocks: Vec<Spanned<RawReadBlock>>,
    pub input_reads_holding: Option<bool>,
    pub combined_commands: Option<Spanned<RawCombinedCommands>>,
    pub source: Option<Spanned<RawCitation>>,
}

/// `{ address, obeys, refusal, source }`: several command bits written at once.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawCombinedCommands {
    pub address: Spanned<i64>,
    pub obeys: String,
    pub refusal: Spanned<i64>,
    pub source: Option<Spanned<RawCitation>>,
}

/// `{ table, address, words, zero_fill, source }`: a read the device answers beyond
/// `max_read_registers`, or across registers no parameter occupies.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawReadBlock {
    pub table: String,
    pub address: i64,
    pub words: i64,
    pub zero_fill: Option<bool>,
    pub source: Option<Spanned<RawCitation>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawCanOpenCaps {
    pub default_node_id: Option<Spanned<i64>>,
    pub lss: Option<Spanned<RawLss>>,
    pub source: Option<Spanned<RawCitation>>,
}

/// `lss = { source }`: the device is an LSS slave (CiA 305), as the cited manual line says.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawLss {
    pub source: Option<Spanned<RawCitation>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawVariant {
    pub name: Spanned<String>,
    pub doc: Option<String>,
    pub selected_by: Option<Spanned<RawVariantSelector>>,
    pub source: Option<Spanned<RawCitation>>,
}

/// `selected_by = { parameter, value }`: the drive is in this variant when it reports `value`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawVariantSelector {
    pub parameter: String,
    pub value: i64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawEnum {
    pub name: Spanned<String>,
    #[serde(rename = "type")]
    pub ty: Spanned<String>,
    pub doc: Option<String>,
    pub source: Option<Spanned<RawCitation>>,
    pub values: Vec<Spanned<RawEnumValue>>,
    pub erratum: Option<String>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawEnumValue {
    pub name: Spanned<String>,
    pub value: Spanned<i64>,
    pub doc: Option<String>,
    pub class: Option<RawValueClass>,
    pub led: Option<Spanned<Vec<u8>>>,
    pub meaning: Option<String>,
}

/// `class = "fault" | "warning"` of an error-code value.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum RawValueClass {
    Fault,
    Warning,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawFlags {
    pub name: Spanned<String>,
    #[serde(rename = "type")]
    pub ty: Spanned<String>,
    pub doc: Option<String>,
    pub source: Option<Spanned<RawCitation>>,
    #[serde(default)]
    pub bits: Vec<Spanned<RawBit>>,
    #[serde(default)]
    pub fields: Vec<Spanned<RawField>>,
    /// The enum of error codes the bits' `code`s are values of.
    pub codes: Option<Spanned<String>>,
    pub erratum: Option<String>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawBit {
    pub name: Spanned<String>,
    pub bit: Spanned<i64>,
    pub doc: Option<String>,
    /// The error code this bit reports (a value of the flags' `codes` enum).
    pub code: Option<Spanned<i64>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawField {
    pub name: Spanned<String>,
    pub lsb: Spanned<i64>,
    pub width: Spanned<i64>,
    pub doc: Option<String>,
    #[serde(rename = "enum")]
    pub enumeration: Option<Spanned<String>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawRecord {
    pub name: Spanned<String>,
    pub kind: Spanned<String>,
    pub index: Spanned<i64>,
    pub doc: Option<String>,
    pub source: Option<Spanned<RawCitation>>,
}

/// A number as written: TOML integers and floats.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(untagged)]
pub enum RawNumber {
    Int(i64),
    Float(f64),
}

/// A `scale` as written.
#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub enum RawScale {
    Int(i64),
    Float(f64),
    Text(String),
    Table(RawScaleTable),
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawScaleTable {
    pub factor: Option<RawScalar>,
    pub offset: Option<RawScalar>,
    pub expr: Option<String>,
}

/// An exact number written as an integer, a float or a string (`"1/100"`).
#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub enum RawScalar {
    Int(i64),
    Float(f64),
    Text(String),
}

/// One inline table or an array of them.
#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub enum OneOrMany<T> {
    One(T),
    Many(Vec<T>),
}

impl<T> OneOrMany<T> {
    pub fn iter(&self) -> std::slice::Iter<'_, T> {
        match self {
            Self::One(one) => std::slice::from_ref(one).iter(),
            Self::Many(many) => many.iter(),
        }
    }

    pub fn into_vec(self) -> Vec<T> {
        match self {
            Self::One(one) => vec![one],
            Self::Many(many) => many,
        }
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawParameter {
    pub name: Spanned<String>,
    pub doc: Option<String>,
    /// Required, except in an overlay entry that matches an EDS object with a `DataType`.
    #[serde(rename = "type")]
    pub ty: Option<Spanned<String>>,
    pub length: Option<Spanned<i64>>,
    pub unit: Option<Spanned<String>>,
    pub scale: Option<Spanned<RawScale>>,
    pub default: Option<Spanned<RawNumber>>,
    pub range: Option<Spanned<Vec<RawNumber>>>,
    pub bounds: Option<Spanned<RawBounds>>,
    pub allowed: Option<Spanned<Vec<RawNumber>>>,
    #[serde(rename = "enum")]
    pub enumeration: Option<Spanned<String>>,
    pub flags: Option<Spanned<String>>,
    pub record: Option<Spanned<String>>,
    // serde cannot keep spans inside an untagged enum, so an address list is located as a whole.
    pub modbus: Option<Spanned<OneOrMany<RawModbusAddress>>>,
    pub canopen: Option<Spanned<OneOrMany<RawCanOpenAddress>>>,
    pub rs232: Option<Spanned<OneOrMany<RawCanOpenAddress>>>,
    pub effect: Option<Spanned<String>>,
    pub command: Option<Spanned<RawCommand>>,
    /// A command register that takes several values (serde keeps no spans inside the untagged
    /// one-or-many form, so several values are a key of their own).
    pub commands: Option<Spanned<Vec<Spanned<RawCommand>>>>,
    pub variants: Option<Vec<Spanned<String>>>,
    pub source: Option<Spanned<RawCitation>>,
    pub erratum: Option<String>,
    /// `safety = true`: a safety-function parameter, read but never written by a plain setter.
    pub safety: Option<bool>,
    /// `stops = true` or `stops = [{ mask, value }]`: the writes that stop the drive.
    pub stops: Option<Spanned<RawStops>>,
}

/// `stops`: every write (`true`), or the values matching one of the patterns.
#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub enum RawStops {
    Every(bool),
    Matching(Vec<RawStopPattern>),
}

/// `{ mask, value, doc }`: the values whose bits under `mask` equal `value`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawStopPattern {
    pub mask: i64,
    pub value: i64,
    /// What the matching values do (documentation only).
    #[allow(dead_code)]
    pub doc: Option<String>,
}

/// `bounds = { min, max, magnitude }`: parameters whose current values bound this one.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawBounds {
    pub min: Option<String>,
    pub max: Option<String>,
    pub magnitude: Option<String>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawModbusAddress {
    pub table: String,
    pub address: i64,
    pub words: Option<i64>,
    pub occupies: Option<i64>,
    pub word_order: Option<String>,
    pub access: Option<String>,
    pub variant: Option<String>,
    pub read_back_of: Option<String>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawCanOpenAddress {
    pub index: i64,
    pub subindex: Option<RawSubindex>,
    pub access: Option<String>,
    pub pdo: Option<RawPdo>,
    pub variant: Option<String>,
}

/// A sub-index: a number, or a run such as `"1..=8"` (see `lower_subindex_range.rs`).
#[derive(Debug, Clone, Deserialize)]
#[serde(untagged)]
pub enum RawSubindex {
    Number(i64),
    Range(String),
}

impl RawSubindex {
    /// The sub-index itself, or the first of a well-formed run (0 when the run is malformed:
    /// lowering reports it).
    pub fn first(&self) -> i64 {
        match self {
            Self::Number(n) => *n,
            Self::Range(text) => {
                crate::load::subindex_range::parse(text).map_or(0, |(first, _)| i64::from(first))
            }
        }
    }
}

#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub enum RawPdo {
    Flag(bool),
    Direction(String),
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawCommand {
    pub kind: Spanned<String>,
    pub value: Option<Spanned<i64>>,
    /// Name of the value when a command register takes several (`[{ kind, value, name }, ...]`).
    pub name: Option<Spanned<String>>,
    pub doc: Option<String>,
}

/// `[cia402]`: how the drive deviates from the CiA 402 state machine.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawCia402 {
    #[serde(default)]
    pub quirks: Vec<Spanned<String>>,
    pub fault_reset_hold_ms: Option<Spanned<i64>>,
    pub sto_bit: Option<Spanned<RawStoBit>>,
    pub source: Option<Spanned<RawCitation>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawStoBit {
    pub parameter: String,
    pub bit: i64,
}

/// `[state_machine]`: a vendor state machine; its states and transitions are `[[state]]` and
/// `[[transition]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawStateMachine {
    pub name: Spanned<String>,
    pub doc: Option<String>,
    pub status: Spanned<String>,
    pub command: Spanned<String>,
    pub initial: Option<Spanned<String>>,
    pub fault: Option<Spanned<String>>,
    pub fault_code: Option<Spanned<String>>,
    pub setpoint: Option<Spanned<String>>,
    pub actual: Option<Spanned<String>>,
    pub communication_loss: Option<Spanned<RawCommunicationLoss>>,

    pub commanded: Option<Spanned<String>>,
    pub coast: Option<Spanned<String>>,
    pub quick_stop: Option<Spanned<String>>,
    pub source: Option<Spanned<RawCitation>>,
}

/// `communication_loss = { timeout, fault }` of a `[state_machine]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawCommunicationLoss {
    pub timeout: String,
    pub fault: u16,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawState {
    pub name: Spanned<String>,
    pub doc: Option<String>,
    pub status: OneOrMany<RawStatusPattern>,
    pub motion: Option<Spanned<String>>,
    pub source: Option<Spanned<RawCitation>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawStatusPattern {
    pub mask: i64,
    pub value: i64,
    pub when: Option<RawCondition>,
    pub speed: Option<String>,
}

/// `{ parameter, value }`: a raw value another parameter must have.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawCondition {
    pub parameter: String,
    pub value: i64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawTransition {
    pub name: Spanned<String>,
    pub doc: Option<String>,
    pub from: OneOrMany<String>,
    pub to: String,
    pub command: Option<Spanned<i64>>,
    pub kind: Option<Spanned<String>>,
    pub source: Option<Spanned<RawCitation>>,
}

/// `only` of an include: a list of names (each with the enums, flags and records it refers to), or
/// one list per kind, taken exactly.
#[derive(Debug, Clone, Deserialize)]
#[serde(untagged)]
pub enum RawOnly {
    Names(Vec<String>),
    Kinds(RawOnlyKinds),
}

#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawOnlyKinds {
    #[serde(default)]
    pub parameters: Vec<String>,
    #[serde(default)]
    pub enums: Vec<String>,
    #[serde(default)]
    pub flags: Vec<String>,
    #[serde(default)]
    pub records: Vec<String>,
}

/// `[[refine]]`: more addresses for, and cited overrides of, a parameter of an included profile.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawRefine {
    pub parameter: Spanned<String>,
    pub doc: Option<String>,
    pub unit: Option<Spanned<String>>,
    pub scale: Option<Spanned<RawScale>>,
    pub default: Option<Spanned<RawNumber>>,
    pub range: Option<Spanned<Vec<RawNumber>>>,
    pub allowed: Option<Spanned<Vec<RawNumber>>>,
    #[serde(rename = "enum")]
    pub enumeration: Option<Spanned<String>>,
    pub modbus: Option<Spanned<OneOrMany<RawModbusAddress>>>,
    pub canopen: Option<Spanned<OneOrMany<RawCanOpenAddress>>>,
    pub rs232: Option<Spanned<OneOrMany<RawCanOpenAddress>>>,
    pub source: Option<Spanned<RawCitation>>,
    pub erratum: Option<String>,
}

/// `[[constant]]`: a value fixed by the product model, usable in scale expressions.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawConstant {
    pub name: Spanned<String>,
    pub doc: Option<String>,
    pub unit: Option<Spanned<String>>,
    pub source: Option<Spanned<RawCitation>>,
}

/// `[[model]]`: a product model the user names when opening the handle, with its constants.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawModel {
    pub name: Spanned<String>,
    pub doc: Option<String>,
    pub constants: Spanned<std::collections::BTreeMap<String, RawScalar>>,
    pub source: Option<Spanned<RawCitation>>,
    pub erratum: Option<String>,
}

/// `exception_functions = [{ request, answer }]`: a device that answers a request's exception
/// under a function code other than `request | 0x80`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawExceptionFunction {
    pub request: i64,
    pub answer: i64,
}
