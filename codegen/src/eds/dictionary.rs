//! The object dictionary an EDS / DCF describes, read from its INI sections.
//!
//! Values stay text here (their meaning depends on the data type); [`super::lower`] interprets
//! them. Everything malformed is a warning and is skipped, except what makes an object unusable.

use std::ops::Range;

use drivebus_model::canopen::NodeId;

use super::parse::{Entry, Ini, Section};
use super::short_text::ShortText;
use super::trim::trim;
use crate::diagnostic::{Diagnostic, FileId, Span};

const RULE_KEY: &str = "eds_unknown_key";
const RULE_OBJECT: &str = "eds_objects";

/// CiA 306 object codes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ObjectKind {
    /// 0x2 DOMAIN: a variable of type DOMAIN.
    Domain,
    /// 0x7 VAR (also when `ObjectType` is missing).
    Var,
    /// 0x8 ARRAY.
    Array,
    /// 0x9 RECORD.
    Record,
}

/// A text value and where it is written. The location is two offsets rather than a [`Span`]:
/// a large EDS has tens of thousands of values, and every byte of a variable is moved twice.
#[derive(Debug, Clone)]
pub struct Text {
    /// The value.
    pub value: ShortText,
    at: u32,
    len: u32,
}

impl Text {
    /// `value`, written at `span` (which must fit `u32` offsets, as every span of a read EDS does).
    pub fn new(value: ShortText, span: &Span) -> Self {
        let offset = |n: usize| u32::try_from(n).unwrap_or(u32::MAX);
        Text {
            value,
            at: offset(span.range.start),
            len: offset(span.range.len()),
        }
    }

    /// Where it is written, in `file` (the file of its variable).
    pub fn span(&self, file: FileId) -> Span {
        let at = self.at as usize;
        Span::new(file, at..at + self.len as usize)
    }
}

/// One variable: a whole VAR / DOMAIN, or one sub-index of an ARRAY / RECORD.
#[derive(Debug, Clone)]
pub struct Variable {
    /// Sub-index (0 for a VAR).
    pub subindex: u8,
    /// `ParameterName`.
    pub name: String,
    /// `Description` (a common non-standard key).
    pub description: Option<String>,
    /// The section header (or the parent's, for compact sub-objects).
    pub span: Span,
    /// The 1-based line of that header.
    pub line: u32,
    /// `DataType`, parsed; `None` when missing or unreadable (reported).
    pub data_type: Option<u16>,
    /// `AccessType` as written.
    pub access: Option<Text>,
    /// `PDOMapping`.
    pub pdo_mapping: bool,
    /// `LowLimit`.
    pub low: Option<Text>,
    /// `HighLimit`.
    pub high: Option<Text>,
    /// `DefaultValue`.
    pub default: Option<Text>,
    /// `ParameterValue` (DCF).
    pub parameter_value: Option<Text>,
    /// For sub-indices 1..=N of a `CompactSubObj=N` object: N. Their keys are the object's, one
    /// text shared by all N (a problem with them is reported once, naming the range).
    pub compact: Option<u8>,
    /// Whether `parameter_value` is this sub-index's own (from `[XXXXValue]`), not shared.
    pub own_value: bool,
}

/// One object (index).
#[derive(Debug, Clone)]
pub struct Object {
    /// Index.
    pub index: u16,
    /// `ParameterName` of an ARRAY / RECORD; empty for a VAR / DOMAIN, whose name is its
    /// variable's (kept once).
    pub name: String,
    /// Object code.
    pub kind: ObjectKind,
    /// The section header.
    pub span: Span,
    /// The 1-based line of the header.
    pub line: u32,
    /// Where its variables are in [`Dictionary::variables`]: the variable of a VAR / DOMAIN, or
    /// the sub-indices of an ARRAY / RECORD.
    pub variables: Range<usize>,
}

/// `[DeviceInfo]`, `[DeviceComissioning]` and `[Comments]`.
#[derive(Debug, Clone, Default)]
pub struct DeviceInfo {
    /// `VendorName`.
    pub vendor_name: Option<String>,
    /// `ProductName`.
    pub product_name: Option<String>,
    /// `NodeID` of a DCF.
    pub node_id: Option<u8>,
    /// `LSS_Supported=1`: the device is an LSS slave (CiA 305).
    pub lss_supported: bool,
    /// `[Comments]` lines.
    pub comments: Vec<String>,
}

/// A whole EDS: identity and objects, ordered by index. The variables of all objects are kept
/// in one vector, in the objects' order: a large EDS has thousands of objects.
#[derive(Debug, Clone, Default)]
pub struct Dictionary {
    /// Identity.
    pub device: DeviceInfo,
    /// Objects by ascending index.
    pub objects: Vec<Object>,
    /// Every object's variables, object after object.
    pub variables: Vec<Variable>,
}

/// A key of an object or sub-index section that drivegen reads.
#[derive(Clone, Copy)]
enum Key {
    ParameterName,
    ObjectType,
    DataType,
    AccessType,
    PdoMapping,
    LowLimit,
    HighLimit,
    DefaultValue,
    ParameterValue,
    SubNumber,
    CompactSubObj,
    Description,
}

/// How many [`Key`]s there are.
const KEYS: usize = Key::Description as usize + 1;

/// What an entry name means in an object or sub-index section.
enum Known {
    /// A key drivegen reads.
    Read(Key),
    /// Known to CiA 306 (or common) but not needed.
    Ignored,
}

/// The key an entry name stands for, in any case; `None` for an unknown key. Dispatching on the
/// length first leaves one or two case-insensitive comparisons per entry.
fn key_of(name: &str) -> Option<Known> {
    let is = |known: &str| is_key(name, known);
    let read = |key| Some(Known::Read(key));
    match name.len() {
        4 if is("unit") => Some(Known::Ignored),
        6 if is("factor") => Some(Known::Ignored),
        8 if is("datatype") => read(Key::DataType),
        8 if is("lowlimit") => read(Key::LowLimit),
        8 if is("objflags") => Some(Known::Ignored),
        9 if is("highlimit") => read(Key::HighLimit),
        9 if is("subnumber") => read(Key::SubNumber),
        10 if is("objecttype") => read(Key::ObjectType),
        10 if is("accesstype") => read(Key::AccessType),
        10 if is("pdomapping") => read(Key::PdoMapping),
        10 if is("denotation") || is("uploadfile") => Some(Known::Ignored),
        11 if is("description") => read(Key::Description),
        12 if is("defaultvalue") => read(Key::DefaultValue),
        12 if is("downloadfile") => Some(Known::Ignored),
        13 if is("parametername") => read(Key::ParameterName),
        13 if is("compactsubobj") => read(Key::CompactSubObj),
        14 if is("parametervalue") => read(Key::ParameterValue),
        15 if is("storagelocation") => Some(Known::Ignored),
        _ => None,
    }
}

/// Whether `name` is `known` (lower-case letters only) in any case. For such a key, setting bit 5
/// of a byte lower-cases a letter and maps no other byte onto a lower-case letter, so keys of 8 to
/// 16 bytes compare as two overlapping words instead of byte by byte.
fn is_key(name: &str, known: &str) -> bool {
    debug_assert!(known.bytes().all(|b| b.is_ascii_lowercase()));
    let (name, known) = (name.as_bytes(), known.as_bytes());
    if name.len() != known.len() || !(8..=16).contains(&name.len()) {
        return name.eq_ignore_ascii_case(known);
    }
    let word = |bytes: &[u8], at: usize| {
        let mut word = [0; 8];
        word.copy_from_slice(&bytes[at..at + 8]);
        u64::from_le_bytes(word)
    };
    let lower = u64::from_le_bytes([0x20; 8]);
    let tail = name.len() - 8;
    word(name, 0) | lower == word(known, 0) && word(name, tail) | lower == word(known, tail)
}

/// The entries of an object or sub-index section by key, found in one pass.
struct ObjectKeys<'s, 't> {
    entries: [Option<&'s Entry<'t>>; KEYS],
    /// Whether some key is none of the known ones (reported once per section).
    has_unknown: bool,
}

impl<'s, 't> ObjectKeys<'s, 't> {
    fn of(section: &Section<'s, 't>) -> Self {
        let mut keys = Self {
            entries: [None; KEYS],
            has_unknown: false,
        };
        for entry in section.entries {
            match key_of(entry.key) {
                // The INI layer already dropped repeated keys.
                Some(Known::Read(key)) => keys.entries[key as usize] = Some(entry),
                Some(Known::Ignored) => {}
                None => keys.has_unknown = true,
            }
        }
        keys
    }

    /// The entry of `key`, if the section has one.
    fn get(&self, key: Key) -> Option<&'s Entry<'t>> {
        self.entries[key as usize]
    }
}

const COMMISSIONING_KEYS: &[&str] = &[
    "nodeid",
    "nodename",
    "baudrate",
    "netnumber",
    "networkname",
    "canopenmanager",
    "lssserialnumber",
];

/// Sections whose content drivegen does not need.
const IGNORED_SECTIONS: &[&str] = &[
    "fileinfo",
    "mandatoryobjects",
    "optionalobjects",
    "manufacturerobjects",
    "tools",
    "dynamicchannels",
    "supportedmodules",
    "connectedmodules",
];

/// Reads the objects of `ini`.
pub fn read(ini: &Ini, diagnostics: &mut Vec<Diagnostic>) -> Dictionary {
    let mut dictionary = Dictionary::default();
    let sections: Vec<Section> = ini.sections().collect();
    let kinds: Vec<SectionKind> = sections.iter().map(|s| classify(s.name)).collect();
    let subs: SubSections = ByIndex::of(&sections, &kinds, |section, kind| match kind {
        SectionKind::Sub(index, sub) => Some((index, (sub, section))),
        _ => None,
    });
    let parents: Parents = ByIndex::of(&sections, &kinds, |section, kind| match kind {
        SectionKind::Object(index) => Some((index, section.span.range.start)),
        _ => None,
    });
    // Room for one variable per object and sub-section: moving grown variables costs megabytes.
    let variables = kinds
        .iter()
        .filter(|k| matches!(k, SectionKind::Object(_) | SectionKind::Sub(..)));
    dictionary.variables.reserve_exact(variables.count());
    for (section, kind) in sections.iter().zip(kinds) {
        match kind {
            SectionKind::Object(index) => {
                let variables = &mut dictionary.variables;
                if let Some(object) = object(ini, &subs, section, index, variables, diagnostics) {
                    dictionary.objects.push(object);
                }
            }
            SectionKind::Sub(index, _) | SectionKind::Names(index) | SectionKind::Values(index) => {
                orphan_check(
                    parents.of_object(index).next().copied(),
                    section,
                    index,
                    diagnostics,
                )
            }
            SectionKind::DeviceInfo => {
                let text = |k: &str| section.get(k).map(|e| e.value.to_owned());
                dictionary.device.vendor_name = text("vendorname");
                dictionary.device.product_name = text("productname");
                dictionary.device.lss_supported = text("lss_supported")
                    .is_some_and(|v| v.trim() == "1" || v.trim().eq_ignore_ascii_case("true"));
            }
            SectionKind::Commissioning => {
                dictionary.device.node_id = commissioning(section, diagnostics)
            }
            SectionKind::Comments => dictionary.device.comments = comments(section),
            SectionKind::DummyUsage => dummy_usage(section, diagnostics),
            SectionKind::Ignored => {}
            SectionKind::Unknown => diagnostics.push(
                Diagnostic::error(RULE_KEY, section.span.clone(), "unknown section is ignored")
                    .warning(),
            ),
        }
    }
    sort_by_index(&mut dictionary);
    dictionary
}

/// Orders the objects by index, and their variables with them (they are usually in order already).
fn sort_by_index(dictionary: &mut Dictionary) {
    if dictionary.objects.is_sorted_by_key(|o| o.index) {
        return;
    }
    dictionary.objects.sort_by_key(|o| o.index);
    let mut unsorted: Vec<Option<Variable>> = std::mem::take(&mut dictionary.variables)
        .into_iter()
        .map(Some)
        .collect();
    for object in &mut dictionary.objects {
        let start = dictionary.variables.len();
        let moved = unsorted[object.variables.clone()]
            .iter_mut()
            .filter_map(Option::take);
        dictionary.variables.extend(moved);
        object.variables = start..dictionary.variables.len();
    }
}

/// Values picked from the sections, sorted by object index, each index's in file order: one
/// vector searched by binary search (vendor files have thousands of sections).
struct ByIndex<T>(Vec<(u16, T)>);

impl<T> ByIndex<T> {
    fn of<'i>(
        sections: &'i [Section<'i, 'i>],
        kinds: &[SectionKind],
        pick: impl Fn(&'i Section<'i, 'i>, SectionKind) -> Option<(u16, T)>,
    ) -> Self {
        let mut picked: Vec<_> = sections
            .iter()
            .zip(kinds)
            .filter_map(|(section, &kind)| pick(section, kind))
            .collect();
        // Stable: one index's values keep their file order.
        picked.sort_by_key(|&(index, _)| index);
        ByIndex(picked)
    }

    /// The values of object `index`. Sized, so that collecting them allocates once.
    fn of_object(&self, index: u16) -> impl ExactSizeIterator<Item = &T> {
        let start = self.0.partition_point(|&(i, _)| i < index);
        let len = self.0[start..].partition_point(|&(i, _)| i == index);
        self.0[start..start + len].iter().map(|(_, value)| value)
    }
}

/// `[XXXXsubN]` sections by object index: sub-index and section.
type SubSections<'i> = ByIndex<(u8, &'i Section<'i, 'i>)>;

/// Where each object's header starts, by object index.
type Parents = ByIndex<usize>;

#[derive(Clone, Copy)]
enum SectionKind {
    Object(u16),
    Sub(u16, u8),
    Names(u16),
    Values(u16),
    DeviceInfo,
    Commissioning,
    Comments,
    DummyUsage,
    Ignored,
    Unknown,
}

/// What a section is, by its name in any ASCII case.
fn classify(name: &str) -> SectionKind {
    let is = |text: &str, lower: &str| text.eq_ignore_ascii_case(lower);
    let index = name
        .get(..4)
        .filter(|h| h.bytes().all(|b| b.is_ascii_hexdigit()))
        .and_then(|h| u16::from_str_radix(h, 16).ok());
    match (index, name.get(4..)) {
        (Some(i), Some("")) => return SectionKind::Object(i),
        (Some(i), Some(rest)) if is(rest, "name") => return SectionKind::Names(i),
        (Some(i), Some(rest)) if is(rest, "value") => return SectionKind::Values(i),
        (Some(i), Some(rest)) => {
            if let Some(sub) = rest
                .get(..3)
                .filter(|prefix| is(prefix, "sub"))
                .and_then(|_| rest.get(3..))
                .filter(|s| !s.is_empty() && s.len() <= 2)
                .and_then(|s| u8::from_str_radix(s, 16).ok())
            {
                return SectionKind::Sub(i, sub);
            }
        }
        _ => {}
    }
    let named = |names: &[&str]| names.iter().any(|n| is(name, n));
    if named(&["deviceinfo"]) {
        SectionKind::DeviceInfo
    } else if named(&["devicecomissioning", "devicecommissioning"]) {
        SectionKind::Commissioning
    } else if named(&["comments"]) {
        SectionKind::Comments
    } else if named(&["dummyusage"]) {
        SectionKind::DummyUsage
    } else if named(IGNORED_SECTIONS) || name.get(..4).is_some_and(|p| is(p, "tool")) {
        SectionKind::Ignored
    } else {
        SectionKind::Unknown
    }
}

/// Sub-sections are read through their parent (whose header starts at `parent`); one without a
/// parent is reported.
fn orphan_check(
    parent: Option<usize>,
    section: &Section,
    index: u16,
    diagnostics: &mut Vec<Diagnostic>,
) {
    match parent {
        None => diagnostics.push(
            Diagnostic::error(
                RULE_OBJECT,
                section.span.clone(),
                format!("section has no parent object `[{index:04X}]`; ignored"),
            )
            .warning(),
        ),
        Some(start) if start > section.span.range.start => diagnostics.push(
            Diagnostic::error(
                RULE_OBJECT,
                section.span.clone(),
                format!("section comes before its parent `[{index:04X}]`"),
            )
            .warning()
            .help("drivegen reads it, but other CANopen tools (python canopen) refuse this order"),
        ),
        Some(_) => {}
    }
}

/// The object of `section`, its variables appended to `variables`.
fn object(
    ini: &Ini,
    subs: &SubSections<'_>,
    section: &Section,
    index: u16,
    variables: &mut Vec<Variable>,
    diagnostics: &mut Vec<Diagnostic>,
) -> Option<Object> {
    let keys = ObjectKeys::of(section);
    let kind = object_kind(&keys, diagnostics)?;
    let mut name = parameter_name(section, &keys, diagnostics, || {
        format!("Object {index:04X}h")
    });
    let start = variables.len();
    match kind {
        ObjectKind::Var | ObjectKind::Domain => {
            warn_subs_of_variable(subs, index, diagnostics);
            let name = std::mem::take(&mut name);
            variables.push(variable(section, &keys, 0, name, diagnostics));
        }
        ObjectKind::Array | ObjectKind::Record => match compact_count(&keys, diagnostics) {
            Some(count) if count > 0 => {
                let object = (section, &keys, index, name.as_str());
                compact(ini, object, count, subs, variables, diagnostics)
            }
            _ => members(subs, &keys, index, variables, diagnostics),
        },
    }
    Some(Object {
        index,
        name,
        kind,
        span: section.span.clone(),
        line: section.line,
        variables: start..variables.len(),
    })
}

fn object_kind(keys: &ObjectKeys, diagnostics: &mut Vec<Diagnostic>) -> Option<ObjectKind> {
    let Some(entry) = keys.get(Key::ObjectType) else {
        return Some(ObjectKind::Var);
    };
    Some(match parse_small(entry.value) {
        Some(0x2) => ObjectKind::Domain,
        Some(0x7) => ObjectKind::Var,
        Some(0x8) => ObjectKind::Array,
        Some(0x9) => ObjectKind::Record,
        // DEFTYPE / DEFSTRUCT define data types, not values a driver reads.
        Some(0x5 | 0x6) => return None,
        _ => {
            diagnostics.push(
                Diagnostic::error(
                    RULE_OBJECT,
                    entry.value_span(),
                    format!("unknown ObjectType `{}`; the object is ignored", entry.value),
                )
                .warning()
                .help("CiA 306 object types: 0x2 DOMAIN, 0x5 DEFTYPE, 0x6 DEFSTRUCT, 0x7 VAR, 0x8 ARRAY, 0x9 RECORD"),
            );
            return None;
        }
    })
}

/// `ParameterName`, or (with a warning) the name `fallback` makes.
fn parameter_name(
    section: &Section,
    keys: &ObjectKeys,
    diagnostics: &mut Vec<Diagnostic>,
    fallback: impl FnOnce() -> String,
) -> String {
    match keys.get(Key::ParameterName) {
        Some(e) if !e.value.is_empty() => e.value.to_owned(),
        _ => {
            let fallback = fallback();
            diagnostics.push(
                Diagnostic::error(RULE_OBJECT, section.span.clone(), "no `ParameterName`")
                    .warning()
                    .label(format!("named `{fallback}`")),
            );
            fallback.to_owned()
        }
    }
}

fn warn_subs_of_variable(subs: &SubSections<'_>, index: u16, diagnostics: &mut Vec<Diagnostic>) {
    for &(_, s) in subs.of_object(index) {
        diagnostics.push(
            Diagnostic::error(
                RULE_OBJECT,
                s.span.clone(),
                "sub-section of a VAR object is ignored",
            )
            .warning()
            .help("give the parent `ObjectType=0x8` (ARRAY) or `0x9` (RECORD)"),
        );
    }
}

fn compact_count(keys: &ObjectKeys, diagnostics: &mut Vec<Diagnostic>) -> Option<u8> {
    let entry = keys.get(Key::CompactSubObj)?;
    let count = parse_small(entry.value).and_then(|n| u8::try_from(n).ok());
    if count.is_none() {
        diagnostics.push(
            Diagnostic::error(
                RULE_OBJECT,
                entry.value_span(),
                "CompactSubObj is not a number of 0..=254 entries; ignored",
            )
            .warning(),
        );
    }
    count.filter(|&c| c < 255)
}

/// Sub-indices of an ARRAY / RECORD from their `[XXXXsubN]` sections.
fn members(
    subs: &SubSections<'_>,
    parent: &ObjectKeys,
    index: u16,
    variables: &mut Vec<Variable>,
    diagnostics: &mut Vec<Diagnostic>,
) {
    let start = variables.len();
    variables.extend(subs.of_object(index).map(|&(sub, s)| {
        let keys = ObjectKeys::of(s);
        if let Some(ot) = keys
            .get(Key::ObjectType)
            .filter(|e| parse_small(e.value) != Some(0x7))
        {
            diagnostics.push(
                Diagnostic::error(
                    RULE_OBJECT,
                    ot.key_span(),
                    "a sub-index is always a VAR; its ObjectType is ignored",
                )
                .warning(),
            );
        }
        let name = parameter_name(s, &keys, diagnostics, || format!("Sub {sub}"));
        variable(s, &keys, sub, name, diagnostics)
    }));
    let members = &mut variables[start..];
    members.sort_by_key(|v| v.subindex);
    if let Some(entry) = parent.get(Key::SubNumber) {
        if parse_small(entry.value) != Some(members.len() as u64) {
            diagnostics.push(
                Diagnostic::error(
                    RULE_OBJECT,
                    entry.value_span(),
                    format!(
                        "SubNumber says {} but {} sub-sections follow",
                        entry.value,
                        members.len()
                    ),
                )
                .warning(),
            );
        }
    }
}

/// `CompactSubObj=N`: sub 0 holds N, subs 1..=N share the object's own description.
fn compact(
    ini: &Ini,
    (section, keys, index, name): (&Section, &ObjectKeys, u16, &str),
    count: u8,
    subs: &SubSections<'_>,
    variables: &mut Vec<Variable>,
    diagnostics: &mut Vec<Diagnostic>,
) {
    let names = ini.section(&format!("{index:04x}name"));
    let values = ini.section(&format!("{index:04x}value"));
    // The up-front reservation counted one variable for this section; it holds count + 1.
    variables.reserve(usize::from(count) + 1);
    let mut template = variable(section, keys, 1, String::new(), diagnostics);
    template.compact = Some(count);
    variables.push(compact_count_entry(
        section,
        index,
        count,
        subs,
        diagnostics,
    ));
    for sub in 1..=count {
        let key = sub.to_string();
        let mut v = template.clone();
        v.subindex = sub;
        v.name = names
            .and_then(|s| s.get(&key))
            .map_or_else(|| format!("{name}{sub}"), |e| e.value.to_owned());
        if let Some(value) = values.and_then(|s| s.get(&key)) {
            v.parameter_value = Some(text(value));
            v.own_value = true;
        }
        variables.push(v);
    }
}

/// Sub 0 of a compact array: its `[XXXXsub0]` section when the EDS has one, else the implicit
/// UNSIGNED8 holding `count`, read-only unless CiA 301 makes it writable
/// ([`sub0_is_writable`]).
fn compact_count_entry(
    section: &Section,
    index: u16,
    count: u8,
    subs: &SubSections<'_>,
    diagnostics: &mut Vec<Diagnostic>,
) -> Variable {
    for &(sub, ignored) in subs.of_object(index).filter(|(sub, _)| *sub != 0) {
        diagnostics.push(
            Diagnostic::error(
                RULE_OBJECT,
                ignored.span.clone(),
                format!("sub-section {sub} of a compact array is ignored: `CompactSubObj={count}` describes subs 1..={count}"),
            )
            .warning()
            .help("name sub-indices in `[XXXXName]`, give their values in `[XXXXValue]`"),
        );
    }
    if let Some(&(_, own)) = subs.of_object(index).find(|(sub, _)| *sub == 0) {
        let keys = ObjectKeys::of(own);
        let name = parameter_name(own, &keys, diagnostics, || "Number of entries".into());
        return variable(own, &keys, 0, name, diagnostics);
    }
    let access = if sub0_is_writable(index) { "rw" } else { "ro" };
    Variable {
        subindex: 0,
        name: "Number of entries".into(),
        description: None,
        data_type: Some(0x0005),
        access: Some(Text::new(ShortText::from(access), section.span)),
        pdo_mapping: false,
        low: None,
        high: None,
        default: Some(Text::new(
            ShortText::from(count.to_string().as_str()),
            section.span,
        )),
        parameter_value: None,
        compact: None,
        own_value: false,
        span: section.span.clone(),
        line: section.line,
    }
}

/// Objects whose sub 0 CiA 301 makes writable: 1003h (writing 0 clears the error history) and
/// the PDO mapping parameters 1600h..17FFh / 1A00h..1BFFh (the number of mapped objects).
pub fn sub0_is_writable(index: u16) -> bool {
    matches!(index, 0x1003 | 0x1600..=0x17FF | 0x1A00..=0x1BFF)
}

fn variable(
    section: &Section,
    keys: &ObjectKeys,
    subindex: u8,
    name: String,
    diagnostics: &mut Vec<Diagnostic>,
) -> Variable {
    if keys.has_unknown {
        for e in section.entries.iter().filter(|e| key_of(e.key).is_none()) {
            diagnostics.push(
                Diagnostic::error(RULE_KEY, e.key_span(), "unknown key is ignored").warning(),
            );
        }
    }
    let text = |entry: Option<&Entry>| entry.map(text);
    let data_type = keys.get(Key::DataType).and_then(|e| {
        let code = parse_small(e.value).and_then(|c| u16::try_from(c).ok());
        if code.is_none() {
            diagnostics.push(
                Diagnostic::error(
                    "eds_data_type",
                    e.value_span(),
                    format!("DataType `{}` is not a number", e.value),
                )
                .warning()
                .label("ignored"),
            );
        }
        code
    });
    let pdo_mapping = keys.get(Key::PdoMapping).is_some_and(|e| {
        let on = parse_small(e.value);
        if !matches!(on, Some(0 | 1)) {
            diagnostics.push(
                Diagnostic::error(
                    RULE_OBJECT,
                    e.value_span(),
                    "PDOMapping is 0 or 1; read as 0",
                )
                .warning(),
            );
        }
        on == Some(1)
    });
    Variable {
        subindex,
        name,
        description: keys.get(Key::Description).map(|e| e.value.to_owned()),
        span: section.span.clone(),
        line: section.line,
        data_type,
        access: text(keys.get(Key::AccessType)),
        pdo_mapping,
        low: text(keys.get(Key::LowLimit)),
        high: text(keys.get(Key::HighLimit)),
        default: text(keys.get(Key::DefaultValue)),
        parameter_value: text(keys.get(Key::ParameterValue)),
        compact: None,
        own_value: false,
    }
}

/// The value of `entry`.
fn text(entry: &Entry) -> Text {
    Text::new(ShortText::from(entry.value), &entry.value_span())
}

fn commissioning(section: &Section, diagnostics: &mut Vec<Diagnostic>) -> Option<u8> {
    for e in section
        .entries
        .iter()
        .filter(|e| !COMMISSIONING_KEYS.iter().any(|k| e.is(k)))
    {
        diagnostics
            .push(Diagnostic::error(RULE_KEY, e.key_span(), "unknown key is ignored").warning());
    }
    let entry = section.get("nodeid")?;
    let id = parse_small(entry.value)
        .and_then(|n| u8::try_from(n).ok())
        .filter(|n| (NodeId::MIN..=NodeId::MAX).contains(n));
    if id.is_none() {
        diagnostics.push(
            Diagnostic::error(
                RULE_OBJECT,
                entry.value_span(),
                "NodeID is not 1..=127; ignored",
            )
            .warning(),
        );
    }
    id
}

fn comments(section: &Section) -> Vec<String> {
    let lines = section
        .get("lines")
        .and_then(|e| parse_small(e.value))
        .unwrap_or(0)
        .min(1000);
    (1..=lines)
        .filter_map(|i| section.get(&format!("line{i}")).map(|e| e.value.to_owned()))
        .collect()
}

fn dummy_usage(section: &Section, diagnostics: &mut Vec<Diagnostic>) {
    for e in section.entries {
        let known = e
            .key
            .get(..5)
            .filter(|p| p.eq_ignore_ascii_case("dummy"))
            .and_then(|_| e.key[5..].parse::<u8>().ok())
            .is_some_and(|n| (1..=0x1B).contains(&n));
        if !known || !matches!(parse_small(e.value), Some(0 | 1)) {
            diagnostics.push(
                Diagnostic::error(
                    RULE_KEY,
                    e.key_span(),
                    "not a `DummyNNNN=0|1` entry; ignored",
                )
                .warning(),
            );
        }
    }
}

/// A small unsigned number in decimal or `0x` hex (with an optional `+`, as `u64::from_str_radix`
/// reads it). Digit by digit: these are a few characters long, read tens of thousands of times.
pub fn parse_small(text: &str) -> Option<u64> {
    let t = trim(text).as_bytes();
    let (digits, radix) = match t {
        [b'0', b'x' | b'X', hex @ ..] => (hex, 16),
        _ => (t, 10),
    };
    let digits = match digits {
        [b'+', rest @ ..] if !rest.is_empty() => rest,
        _ => digits,
    };
    if digits.is_empty() {
        return None;
    }
    digits.iter().try_fold(0u64, |n, &b| {
        let digit = char::from(b).to_digit(radix)?;
        n.checked_mul(radix.into())?.checked_add(digit.into())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_match_in_any_case_and_nothing_else() {
        for (name, known) in [
            ("DataType", "datatype"),
            ("PARAMETERNAME", "parametername"),
            ("storageLocation", "storagelocation"),
            ("Unit", "unit"),
        ] {
            assert!(is_key(name, known), "{name}");
        }
        for (name, known) in [
            ("DataTypf", "datatype"),
            ("Data@ype", "datatype"),
            ("DataType ", "datatype"),
            ("ParameterNa_e", "parametername"),
            ("Uni", "unit"),
        ] {
            assert!(!is_key(name, known), "{name}");
        }
    }

    #[test]
    fn small_numbers_read_as_from_str_radix_reads_them() {
        for text in [
            "0",
            "7",
            " 0x7 ",
            "0X1f",
            "+5",
            "0x+5",
            "+",
            "0x",
            "-1",
            "1a",
            "0xg",
            "18446744073709551615",
            "18446744073709551616",
            "0xFFFFFFFFFFFFFFFF",
            "",
        ] {
            let t = text.trim();
            let expected = match t.strip_prefix("0x").or_else(|| t.strip_prefix("0X")) {
                Some(hex) => u64::from_str_radix(hex, 16).ok(),
                None => t.parse().ok(),
            };
            assert_eq!(parse_small(text), expected, "{text:?}");
        }
    }
}
