//! The IR: the one normalized device model every emitter and check reads.
//!
//! `drivegen dump --json` serializes it; the schema is documented in `docs/ir-json.md` and is
//! stable: fields are only ever added. Spans are kept for diagnostics and never serialized.

mod bounds;
mod data_type;
mod expected_identity;
mod expr;
mod identity_checks;
mod indexed;
mod lock;
mod lock_view;
mod machine_view;
mod mapping;
mod mapping_json;
mod model;
mod node_ids;
mod ramp;
mod read_block;
mod readable_registers;
mod refinement;
mod run_time_model;
mod safety;
mod scale_inputs;
mod stop_writes;
mod value_type;
mod variant_selector;

pub use bounds::Bounds;
pub use data_type::DataType;
pub use drivebus_model::{Number, Range};
pub use expected_identity::ExpectedIdentity;
pub use expr::{Expr, ExprError, Op};
pub use identity_checks::{Covered, IdentityCheck};
pub use indexed::IndexedParameter;
pub use lock::{
    Grant, GrantKey, Lock, LockScope, Requirement, TimeoutAction, TimeoutEffect, Unlock, UnlockEnd,
    Watchdog,
};
pub use mapping::{
    pdo_bits, CobId, Direction, Mapping, MappingKind, PdoDefaults, SrdoCobId, SrdoDefaults,
};
pub use model::{Constant, Model};
pub use node_ids::{DefaultCheck, NodeIds};
pub use ramp::{per_second, Polarity, Ramp, Slope};
pub use read_block::ReadBlock;
pub use refinement::Refinement;
pub use safety::is_safety_configuration;
pub use stop_writes::StopWrites;
pub use value_type::ValueType;
pub use variant_selector::VariantSelector;

/// The Modbus vocabulary is the runtime's own: the IR names the types generated code uses.
pub use drivebus_model::modbus::{Table, WordOrder};

use std::sync::Arc;

use serde::Serialize;

use crate::diagnostic::Span;

/// Version of the IR JSON schema.
pub const IR_SCHEMA_VERSION: u32 = 1;

/// A whole device (or a profile).
#[derive(Debug, Clone, Serialize)]
pub struct Device {
    /// IR JSON schema version.
    pub schema: u32,
    /// Identity and provenance.
    pub device: Identity,
    /// Manuals cited.
    pub sources: Vec<SourceDoc>,
    /// Modbus capabilities, if the device speaks Modbus.
    pub modbus: Option<ModbusCaps>,
    /// CANopen capabilities, if the device speaks CANopen.
    pub canopen: Option<CanOpenCaps>,
    /// The drive, firmware and configuration the description covers (`[identity]`), if given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub identity: Option<ExpectedIdentity>,
    /// Writes refused until the drive is unlocked (`[lock]`, `[[unlock]]`, `[watchdog]`), if any.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lock: Option<Lock>,
    /// Firmware / configuration variants; the first is the default.
    pub variants: Vec<Variant>,
    /// Enumerations.
    pub enums: Vec<Enum>,
    /// Bit-field words.
    pub flags: Vec<Flags>,
    /// CANopen records and arrays.
    pub records: Vec<Record>,
    /// Parameters.
    pub parameters: Vec<Parameter>,
    /// CiA 402 state machine quirks (`[cia402]`), if declared.
    pub cia402: Option<Cia402>,
    /// A vendor state machine (`[state_machine]`, `[[state]]`, `[[transition]]`), if declared.
    pub state_machine: Option<StateMachine>,
    /// How fast the speed follows each setpoint (`[[ramp]]`), left out of the JSON when none.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub ramps: Vec<Ramp>,
    /// Declared PDOs and SRDOs, PDOs first, each kind in declaration order (in the JSON as
    /// `pdos` and `srdos`, each left out when there are none).
    #[serde(flatten, serialize_with = "mapping_json::by_kind")]
    pub mappings: Vec<Mapping>,
    /// Members described once over a run of sub-indices (left out of the JSON when there are none).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub indexed: Vec<IndexedParameter>,
    /// `[[refine]]` entries applied to included parameters (left out of the JSON when none).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub refinements: Vec<Refinement>,
    /// Per-model constants (`[[constant]]`), left out of the JSON when none.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub constants: Vec<Constant>,
    /// Product models (`[[model]]`) and their constants, left out of the JSON when none.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub models: Vec<Model>,
}

/// How the drive deviates from the CiA 402 state machine.
#[derive(Debug, Clone, Serialize)]
pub struct Cia402 {
    /// Quirk names, as `drivebus::control::Quirk::name` spells them.
    pub quirks: Vec<String>,
    /// Minimum time fault reset (controlword bit 7) is held high, in milliseconds.
    pub fault_reset_hold_ms: u32,
    /// Where safe torque off shows, if the drive reports it.
    pub sto_bit: Option<StoBit>,
    /// Citation.
    pub source: Option<Citation>,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

/// A bit of a 16-bit parameter that is set while safe torque off is active.
#[derive(Debug, Clone, Serialize)]
pub struct StoBit {
    /// The parameter.
    pub parameter: String,
    /// The bit.
    pub bit: u8,
}

/// A vendor state machine: states recognised from a status parameter, transitions commanded by
/// writing a command parameter.
#[derive(Debug, Clone, Serialize)]
pub struct StateMachine {
    /// snake_case name.
    pub name: String,
    /// Documentation.
    pub doc: Option<String>,
    /// The parameter states are recognised from.
    pub status: String,
    /// The parameter commands are written to.
    pub command: String,
    /// The state the drive powers up in: the declared one, else the first state no transition
    /// enters, else the first state.
    pub initial: String,
    /// The state a drive fault leads to, if the description names one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fault: Option<String>,
    /// The parameter that shows the active fault's code.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fault_code: Option<String>,
    /// The setpoint the motor follows in states whose motion is `follow`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub setpoint: Option<String>,
    /// The parameter that shows the speed the motor turns at, in the setpoint's raw units (the
    /// simulator's motor shows its speed there, besides the CiA 402 actual values).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub actual: Option<String>,
    /// The drive faults when no request arrives for a while as the motor runs.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub communication_loss: Option<CommunicationLoss>,

    /// The parameter that shows the speed the motor heads for (0 while the power stage is off),
    /// in the setpoint's raw units (Lenze smd #24 Command Speed).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub commanded: Option<String>,
    /// The state the drive enters when it coasts to a stop on its own (a `[watchdog]` action
    /// `coast`), if the description names one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub coast: Option<String>,
    /// The state the drive enters when it quick-stops on its own (a `[watchdog]` action
    /// `quick_stop`), if the description names one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub quick_stop: Option<String>,
    /// States, in recognition order (the first match wins).
    pub states: Vec<MachineState>,
    /// Transitions.
    pub transitions: Vec<Transition>,
    /// Citation.
    pub source: Option<Citation>,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

/// Communication loss supervision of a vendor state machine (Lafert: "if the drive doesn't
/// receive a valid Modbus message within the communication loss time while the motor runs, it
/// goes to alarm 0x7521 and the motor coasts", Modbus manual lines 809, 1276-1279, 458).
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct CommunicationLoss {
    /// The integer parameter holding the time allowed without a request (unit `ms` or `s`; 0
    /// switches the supervision off).
    pub timeout: String,
    /// The fault code the drive raises on a loss (entering the machine's `fault` state).
    pub fault: u16,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

/// A state of a vendor state machine.
#[derive(Debug, Clone, Serialize)]
pub struct MachineState {
    /// snake_case name.
    pub name: String,
    /// Documentation.
    pub doc: Option<String>,
    /// The state shows when `status & mask == value` for any pattern.
    pub status: Vec<StatusPattern>,
    /// What the power stage does in this state.
    pub motion: Motion,
    /// Citation.
    pub source: Option<Citation>,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

/// One way a state shows in the status parameter.
#[derive(Debug, Clone, Serialize)]
pub struct StatusPattern {
    /// Bits that decide.
    pub mask: u16,
    /// Their values.
    pub value: u16,
    /// The pattern a drive shows only while another parameter has a given value (Lafert: RUN in
    /// torque mode shows bit 5 instead of bit 0).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub when: Option<Condition>,
    /// The pattern a drive shows only while its speed is in this phase (Lenze smd: ACCEL, DECEL,
    /// RUN, RUN AT 0Hz of one running state).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub speed: Option<SpeedPhase>,
}

/// Where the motor's speed is relative to the speed it is heading for, while the power stage
/// drives it (`follow` and `ramp-stop` states).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum SpeedPhase {
    /// Moving away from zero towards the target.
    Rising,
    /// Moving towards zero (a lower target, or a ramp to a stop).
    Falling,
    /// At a target other than zero.
    Steady,
    /// At zero with a target of zero.
    Zero,
}

/// `parameter == value`, on the raw value.
#[derive(Debug, Clone, Serialize)]
pub struct Condition {
    /// The parameter.
    pub parameter: String,
    /// Its raw value.
    pub value: i64,
}

/// What the power stage does in a state of a vendor state machine.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Motion {
    /// Disabled: the motor follows nothing.
    #[default]
    Disabled,
    /// Enabled, following the machine's setpoint.
    Follow,
    /// Stopping at once, holding with maximum torque.
    QuickStop,
    /// Ramping to zero along the setpoint's deceleration ramp, then holding zero.
    RampStop,
}

/// What causes a transition.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum TransitionKind {
    /// Writing `command` to the command parameter.
    Command,
    /// The drive moves by itself.
    Automatic,
    /// An event outside the master's control (safety input, fault, reset input).
    External,
}

/// A transition of a vendor state machine.
#[derive(Debug, Clone, Serialize)]
pub struct Transition {
    /// Name as in the manual.
    pub name: String,
    /// Documentation.
    pub doc: Option<String>,
    /// States it leaves.
    pub from: Vec<String>,
    /// State it enters.
    pub to: String,
    /// What causes it.
    pub kind: TransitionKind,
    /// The value written to the command parameter (command transitions only).
    pub command: Option<u16>,
    /// Citation.
    pub source: Option<Citation>,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

/// Who the device is and where the description comes from.
#[derive(Debug, Clone, Serialize)]
pub struct Identity {
    /// Human name.
    pub name: String,
    /// Rust type name of the drive handle.
    pub handle: String,
    /// Vendor.
    pub vendor: Option<String>,
    /// Firmware the description was written against.
    pub firmware: Option<String>,
    /// Documentation.
    pub doc: Option<String>,
    /// Citation.
    pub source: Option<Citation>,
    /// True for a profile fragment (no `[device]`).
    pub is_profile: bool,
}

/// A manual.
#[derive(Debug, Clone, Serialize)]
pub struct SourceDoc {
    /// Short id cited by `source.doc`.
    pub id: String,
    /// File name or URL.
    pub file: String,
    /// Title.
    pub title: String,
    /// A published standard (CiA 402) rather than a manual in shared/seeds: cited by section,
    /// without a line. Left out of the JSON when false.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub standard: bool,
}

/// A cited manual as its citations name it: one per manual, shared by all of them (a description
/// cites a few documents thousands of times).
#[derive(Debug, Serialize, Default, PartialEq, Eq)]
pub struct CitedDoc {
    /// `SourceDoc::id`.
    pub doc: String,
    /// The `SourceDoc::file` it resolves to.
    pub file: String,
    /// `SourceDoc::standard`: cited by section, without a line. Left out of the JSON when false.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub standard: bool,
}

impl CitedDoc {
    /// The document `doc` in `file`, ready to share.
    pub fn shared(doc: &str, file: &str) -> Arc<Self> {
        Arc::new(CitedDoc {
            doc: doc.to_owned(),
            file: file.to_owned(),
            standard: false,
        })
    }

    /// The published standard `doc` (CiA 402), cited by section, ready to share.
    pub fn standard(doc: &str, title: &str) -> Arc<Self> {
        Arc::new(CitedDoc {
            doc: doc.to_owned(),
            file: title.to_owned(),
            standard: true,
        })
    }
}

/// A place in a manual.
#[derive(Debug, Clone, Serialize, Default)]
pub struct Citation {
    /// The manual (serialized as its `doc` and `file`).
    #[serde(flatten)]
    pub cited: Arc<CitedDoc>,
    /// Section.
    pub section: Option<String>,
    /// Line in the file.
    pub line: Option<u32>,
    /// A worked example quoted from the manual.
    pub example: Option<String>,
    /// The manual's own name of the register or object (`"BUS DC LINK"`, `"C01"`), a search
    /// alias of the generated item. Left out of the JSON when absent.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Where the citation is written.
    #[serde(skip)]
    pub span: Span,
}

impl Citation {
    /// `SourceDoc::id` of the manual.
    pub fn doc(&self) -> &str {
        &self.cited.doc
    }

    /// The `SourceDoc::file` of the manual.
    pub fn file(&self) -> &str {
        &self.cited.file
    }
}

/// The device's Modbus capabilities.
#[derive(Debug, Clone, Serialize)]
pub struct ModbusCaps {
    /// Most registers per read.
    pub max_read_registers: u16,
    /// Most registers per write.
    pub max_write_registers: u16,
    /// Function codes implemented.
    pub functions: Vec<u8>,
    /// Whether unit id 0 is accepted.
    pub broadcast: bool,
    /// Whether reads may span undocumented addresses.
    pub read_gaps: bool,
    /// Default word order.
    pub word_order: WordOrder,
    /// Exception code for an illegal address.
    pub illegal_address_exception: u8,
    /// Exception code for an illegal value.
    pub illegal_value_exception: u8,
    /// Reads the device answers beyond `max_read_registers` (Lenze smd: 6 words at #24).
    pub read_blocks: Vec<ReadBlock>,
    /// Requests whose exception the device answers under another function code than
    /// `request | 0x80` (left out of the JSON when none).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub exception_functions: Vec<ExceptionFunction>,
    /// Whether FC 04 (read input registers) reads the holding table: the device does not tell 3X
    /// from 4X references (Lenze smd, line 237). Left out of the JSON when false.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub input_reads_holding: bool,
    /// What the device does with a write to a command register that sets several commands' bits
    /// at once (Lenze smd #1, lines 569-571), left out of the JSON when not described.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub combined_commands: Option<CombinedCommands>,
    /// Citation.
    pub source: Option<Citation>,
    /// The register lists of [`Device::modbus_limits`], derived on first use.
    #[serde(skip)]
    pub(crate) register_lists: readable_registers::RegisterListsCell,
}

/// The rule of a command register whose commands are one bit each, for a write that sets several
/// (`[modbus] combined_commands`): the device obeys `obeys` alone when its bits are among them,
/// and answers `refusal` otherwise.
#[derive(Debug, Clone, Serialize)]
pub struct CombinedCommands {
    /// The holding register the commands share.
    pub address: u16,
    /// The command parameter obeyed alone when its trigger bits are set among others.
    pub obeys: String,
    /// The exception code of a write setting several bits without those of `obeys`.
    pub refusal: u8,
    /// Citation.
    pub source: Option<Citation>,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

impl ModbusCaps {
    /// Whether the device implements FC 0x10 (write multiple registers); without it, values of
    /// several registers are written register by register.
    pub fn writes_multiple_registers(&self) -> bool {
        self.functions.contains(&0x10)
    }
}

/// A request whose exception answer carries a deviating function code.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct ExceptionFunction {
    /// The request's function code.
    pub request: u8,
    /// The function code of its exception answer (bit 7 set).
    pub answer: u8,
}

impl ModbusCaps {
    /// The function code the device answers an exception to `request` with.
    pub fn exception_function(&self, request: u8) -> u8 {
        self.exception_functions
            .iter()
            .find(|e| e.request == request)
            .map_or(request | 0x80, |e| e.answer)
    }
}

/// The device's CANopen capabilities.
#[derive(Debug, Clone, Serialize)]
pub struct CanOpenCaps {
    /// Node id out of the box.
    pub default_node_id: u8,
    /// The device is an LSS slave (CiA 305): node id and bit rate can be set over LSS.
    /// `None` when the manual does not say so.
    pub lss: Option<Lss>,
    /// Citation.
    pub source: Option<Citation>,
}

/// LSS (CiA 305) support, as the manual states it.
#[derive(Debug, Clone, Serialize)]
pub struct Lss {
    /// Citation of the manual's statement.
    pub source: Option<Citation>,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

/// A firmware or parameter-configuration variant.
#[derive(Debug, Clone, Serialize)]
pub struct Variant {
    /// snake_case name.
    pub name: String,
    /// Documentation.
    pub doc: Option<String>,
    /// The value of a parameter by which the drive reports this variant. Left out of the JSON
    /// when absent.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub selected_by: Option<VariantSelector>,
    /// Citation.
    pub source: Option<Citation>,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

/// An open enumeration.
#[derive(Debug, Clone, Serialize)]
pub struct Enum {
    /// snake_case name.
    pub name: String,
    /// Integer type.
    /// Serialized as `type`, plus `length` for strings and octets.
    #[serde(flatten)]
    pub data_type: DataType,
    /// Documentation.
    pub doc: Option<String>,
    /// Values.
    pub values: Vec<EnumValue>,
    /// Citation.
    pub source: Option<Citation>,
    /// Errata decision.
    pub erratum: Option<String>,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

/// One value of an enumeration.
#[derive(Debug, Clone, Serialize)]
pub struct EnumValue {
    /// snake_case name.
    pub name: String,
    /// Raw value.
    pub value: i64,
    /// Documentation.
    pub doc: Option<String>,
    /// For error codes: whether the value is a fault (the drive stops) or a warning.
    pub class: Option<ValueClass>,
    /// For error codes: the LED blink code, `[first, second]` (e.g. green, then yellow blinks).
    pub led: Option<[u8; 2]>,
    /// For error codes: what the value means and what to do, apart from its one-line `doc`.
    pub meaning: Option<String>,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

/// Class of an error-code value.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ValueClass {
    /// The drive stops and needs a fault reset.
    Fault,
    /// The drive keeps running and signals the condition.
    Warning,
}

/// A bit-field word.
#[derive(Debug, Clone, Serialize)]
pub struct Flags {
    /// snake_case name.
    pub name: String,
    /// Unsigned integer type.
    /// Serialized as `type`, plus `length` for strings and octets.
    #[serde(flatten)]
    pub data_type: DataType,
    /// Documentation.
    pub doc: Option<String>,
    /// Single-bit flags.
    pub bits: Vec<Bit>,
    /// Multi-bit fields.
    pub fields: Vec<BitField>,
    /// The enum of error codes the bits report (`bits[].code`), left out of the JSON when none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub codes: Option<String>,
    /// Citation.
    pub source: Option<Citation>,
    /// Errata decision.
    pub erratum: Option<String>,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

/// One flag bit.
#[derive(Debug, Clone, Serialize)]
pub struct Bit {
    /// snake_case name.
    pub name: String,
    /// Bit number, 0 = least significant.
    pub bit: u32,
    /// Documentation.
    pub doc: Option<String>,
    /// The error code the bit reports, a value of the flags' `codes` enum (left out of the JSON
    /// when none).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub code: Option<i64>,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

/// A multi-bit field.
#[derive(Debug, Clone, Serialize)]
pub struct BitField {
    /// snake_case name.
    pub name: String,
    /// Least significant bit.
    pub lsb: u32,
    /// Width in bits.
    pub width: u32,
    /// Documentation.
    pub doc: Option<String>,
    /// Enumeration of the field's values.
    #[serde(rename = "enum")]
    pub enumeration: Option<String>,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

/// Record or array.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum RecordKind {
    /// CiA 301 RECORD (object code 0x9).
    Record,
    /// CiA 301 ARRAY (object code 0x8).
    Array,
}

/// A CANopen record or array; its members are parameters naming it.
#[derive(Debug, Clone, Serialize)]
pub struct Record {
    /// snake_case name.
    pub name: String,
    /// Record or array.
    pub kind: RecordKind,
    /// Object index.
    pub index: u16,
    /// Documentation.
    pub doc: Option<String>,
    /// Citation.
    pub source: Option<Citation>,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

/// Access over one protocol address.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Access {
    /// Readable.
    pub read: bool,
    /// Writable.
    pub write: bool,
}

/// A Modbus address of a parameter: the wire address generated code uses, plus what the
/// description says of it.
#[derive(Debug, Clone, Serialize)]
pub struct ModbusAddress {
    /// Table, PDU address, registers occupied and word order.
    #[serde(flatten)]
    pub wire: drivebus_model::modbus::ModbusAddress,
    /// Registers of the map the value occupies from `address`: `words`, unless the device
    /// answers a read of `words` words at this one address (Lenze smd C99: 4 words, 1 register).
    pub occupies: u16,
    /// Access.
    pub access: Access,
    /// Variant this address is limited to.
    pub variant: Option<String>,
    /// The parameter whose register this address reads back, where the device has no register
    /// of this parameter's own (Kinco FD: no 6061h over Modbus; the mode display is 6060h's
    /// register 0x3500 read back). The register belongs to that parameter
    /// (`read_backs_share_their_register`).
    pub read_back_of: Option<String>,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

/// `address.table`, `address.words`, ...: a described address is first of all its wire address.
impl std::ops::Deref for ModbusAddress {
    type Target = drivebus_model::modbus::ModbusAddress;

    fn deref(&self) -> &Self::Target {
        &self.wire
    }
}

/// PDO mappability.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Pdo {
    /// Not mappable.
    None,
    /// Mappable into receive PDOs (master → drive).
    Rx,
    /// Mappable into transmit PDOs (drive → master).
    Tx,
    /// Both directions.
    Both,
}

/// A CANopen (or Kinco RS-232) object address of a parameter.
#[derive(Debug, Clone, Serialize)]
pub struct ObjectAddress {
    /// Index.
    pub index: u16,
    /// Subindex.
    pub subindex: u8,
    /// Access.
    pub access: Access,
    /// Constant object (CiA 306 `const`).
    pub constant: bool,
    /// PDO mappability.
    pub pdo: Pdo,
    /// Variant this address is limited to.
    pub variant: Option<String>,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

/// How raw values become engineering values.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Scale {
    /// `raw × factor + offset`, exact; serialized as the factor's `numerator` and
    /// `denominator` beside the `offset` ratio.
    Fixed(drivebus_model::Scale),
    /// A factor computed at run time from other parameters.
    Runtime {
        /// The expression as written.
        expr: String,
        /// The parameters it reads.
        inputs: Vec<String>,
        /// The parsed expression.
        #[serde(skip)]
        ast: Expr,
    },
}

/// When a written value takes effect.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Effect {
    /// At once.
    #[default]
    Immediate,
    /// After a device reset.
    AfterReset,
    /// After storing to non-volatile memory and a reset.
    AfterStoreReset,
}

/// What a command register does.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum CommandKind {
    /// Store parameters to non-volatile memory.
    Store,
    /// Restore factory parameters.
    RestoreFactory,
    /// Reset the device.
    Reset,
    /// Any other action.
    Action,
}

/// A command register.
#[derive(Debug, Clone, Serialize)]
pub struct Command {
    /// What it does.
    pub kind: CommandKind,
    /// The raw value that triggers it.
    pub value: Option<i64>,
    /// Name of this value, where the register takes several.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Documentation of this value.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub doc: Option<String>,
    /// The register's further command values (2FF0h sub 1 of Kinco: 1 = store, 10 =
    /// initialise), left out of the JSON when none.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub more: Vec<Command>,
}

impl Command {
    /// Every value of the command register, the first one first.
    pub fn values(&self) -> impl Iterator<Item = &Command> {
        std::iter::once(self).chain(&self.more)
    }
}

/// A parameter.
#[derive(Debug, Clone, Serialize)]
pub struct Parameter {
    /// snake_case name.
    pub name: String,
    /// Documentation.
    pub doc: Option<String>,
    /// Data type.
    /// Serialized as `type`, plus `length` for strings and octets.
    #[serde(flatten)]
    pub data_type: DataType,
    /// Unit symbol.
    pub unit: Option<String>,
    /// Scaling.
    pub scale: Option<Scale>,
    /// Raw default.
    pub default: Option<Number>,
    /// The default is `node id + default` (a CiA 306 `$NODEID+...` value, e.g. a COB-ID): it differs
    /// on every node, so it is kept symbolic.
    pub default_plus_node_id: bool,
    /// Raw range.
    pub range: Option<Range>,
    /// Parameters whose current values bound this one (checked at run time). Left out of the
    /// JSON when absent, so descriptions without bounds dump as before.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bounds: Option<Bounds>,
    /// The writes that stop the drive (`stops`), never refused client-side. Left out of the
    /// JSON when absent.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stops: Option<StopWrites>,
    /// Allowed raw values.
    pub allowed: Vec<Number>,
    /// Enumeration of the value.
    #[serde(rename = "enum")]
    pub enumeration: Option<String>,
    /// Bit-field type of the value.
    pub flags: Option<String>,
    /// Record this is a member of.
    pub record: Option<String>,
    /// Modbus addresses.
    pub modbus: Vec<ModbusAddress>,
    /// CANopen addresses.
    pub canopen: Vec<ObjectAddress>,
    /// Kinco RS-232 addresses.
    pub rs232: Vec<ObjectAddress>,
    /// When a write takes effect.
    pub effect: Effect,
    /// Command register.
    pub command: Option<Command>,
    /// Variants the parameter exists in (empty = all).
    pub variants: Vec<String>,
    /// Citation.
    pub source: Option<Citation>,
    /// Errata decision.
    pub erratum: Option<String>,
    /// A safety-function parameter (`safety = true`): the generated API reads it but gives it no
    /// setter (see [`Parameter::is_safety`]). Left out of the IR JSON when false.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub safety: bool,
    /// Where things are declared.
    #[serde(skip)]
    pub spans: ParameterSpans,
}

/// Source locations of a parameter's keys, for diagnostics.
#[derive(Debug, Clone, Default)]
pub struct ParameterSpans {
    /// The name.
    pub name: Span,
    /// The type.
    pub data_type: Span,
    /// The default.
    pub default: Option<Span>,
    /// The range.
    pub range: Option<Span>,
    /// The allowed values.
    pub allowed: Option<Span>,
    /// The scale.
    pub scale: Option<Span>,
    /// The unit.
    pub unit: Option<Span>,
    /// The enum reference.
    pub enumeration: Option<Span>,
    /// The flags reference.
    pub flags: Option<Span>,
    /// The record reference.
    pub record: Option<Span>,
    /// The variants list.
    pub variants: Vec<Span>,
}

impl Parameter {
    /// Whether a value is one of the allowed values (always, when the description lists none),
    /// given how it compares with each.
    pub fn allows(&self, compare: impl Fn(Number) -> Option<std::cmp::Ordering>) -> bool {
        self.allowed.is_empty()
            || self
                .allowed
                .iter()
                .any(|a| compare(*a) == Some(std::cmp::Ordering::Equal))
    }
}

impl Device {
    /// A parameter by name.
    pub fn parameter(&self, name: &str) -> Option<&Parameter> {
        self.parameters.iter().find(|p| p.name == name)
    }
    /// An enumeration by name.
    pub fn enumeration(&self, name: &str) -> Option<&Enum> {
        self.enums.iter().find(|e| e.name == name)
    }
    /// A flags type by name.
    pub fn flags_type(&self, name: &str) -> Option<&Flags> {
        self.flags.iter().find(|f| f.name == name)
    }
}

impl Access {
    /// Read-only.
    pub const READ: Access = Access {
        read: true,
        write: false,
    };
    /// Write-only.
    pub const WRITE: Access = Access {
        read: false,
        write: true,
    };
    /// Read/write.
    pub const READ_WRITE: Access = Access {
        read: true,
        write: true,
    };
}
