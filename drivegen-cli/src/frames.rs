//! A CANopen frame as people and tools read it: named, typed, with the parameter values it
//! carries. `decode` prints these; `trace` filters and triggers on them.
//!
//! A frame decodes into borrowed values: the classified message, and the values it carries with
//! the parameters they belong to (by reference into the description's index, `objects.rs`).
//! Its text (object names, typed values, units) is written only when the frame is printed, so a
//! frame a filter drops costs no formatting and no allocation (issue 33, docs/benchmarks.md).

use std::collections::BTreeSet;
use std::fmt;

use drivebus::canopen::message::Message;
use drivebus::canopen::sdo::AbortCode;
use drivebus::canopen::CanFrame;
use drivebus::trace::Event;
use smallvec::SmallVec;

use crate::objects::{Known, Objects};
use crate::pdo_mappings::PdoMappings;

/// A parameter value a frame carries: its bytes and the object they belong to.
#[derive(Debug, Clone, Copy)]
pub struct Sample<'a> {
    known: Option<&'a Known<'a>>,
    index: u16,
    subindex: u8,
    len: u8,
    bytes: [u8; 8],
}

/// The values of one frame: a frame carries at most a few (an SDO one, a PDO up to eight bytes).
pub type Samples<'a> = SmallVec<[Sample<'a>; 4]>;

impl<'a> Sample<'a> {
    /// The value of `bytes` (at most 8; more are cut) at `index:subindex` of `objects`.
    pub fn of(objects: &'a Objects<'a>, index: u16, subindex: u8, bytes: &[u8]) -> Self {
        let len = bytes.len().min(8);
        let mut copy = [0u8; 8];
        copy[..len].copy_from_slice(&bytes[..len]);
        Self {
            known: objects.find(index, subindex),
            index,
            subindex,
            len: len as u8,
            bytes: copy,
        }
    }

    fn bytes(&self) -> &[u8] {
        &self.bytes[..usize::from(self.len)]
    }

    /// The name of the parameter, if the description has the object.
    pub fn name(&self) -> Option<&'a str> {
        self.known.map(|k| k.parameter.name.as_str())
    }

    /// The parameter's name, or `INDEX:SUB` for an object the description does not have.
    pub fn parameter(&self) -> impl fmt::Display + use<'_, 'a> {
        ObjectName {
            known: self.known,
            index: self.index,
            subindex: self.subindex,
        }
    }

    /// The value for people, with its unit or names (the bytes, for an unknown object).
    pub fn text(&self) -> impl fmt::Display + use<'_, 'a> {
        fmt_with(move |f| match self.known {
            Some(known) => write!(f, "{}", known.presentation.text(self.bytes())),
            None => write!(f, "{:02X?}", self.bytes()),
        })
    }

    /// The value as a number (an enumeration or flags word by its raw value), if it is one.
    pub fn value(&self) -> Option<f64> {
        self.known?.presentation.number(self.bytes())
    }
}

/// A parameter's name, or the address of an object the description does not have.
struct ObjectName<'a> {
    known: Option<&'a Known<'a>>,
    index: u16,
    subindex: u8,
}

impl fmt::Display for ObjectName<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.known {
            Some(known) => f.write_str(&known.parameter.name),
            None => write!(f, "{:04X}:{:02X}", self.index, self.subindex),
        }
    }
}

/// A `Display` of a closure (`fmt::from_fn` is newer than the workspace's Rust version).
fn fmt_with<F: Fn(&mut fmt::Formatter<'_>) -> fmt::Result>(f: F) -> impl fmt::Display {
    struct With<F>(F);
    impl<F: Fn(&mut fmt::Formatter<'_>) -> fmt::Result> fmt::Display for With<F> {
        fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            (self.0)(f)
        }
    }
    With(f)
}

/// One decoded frame.
#[derive(Debug, Clone)]
pub struct Decoded<'a> {
    objects: &'a Objects<'a>,
    message: Message,
    samples: Samples<'a>,
    /// The value is the samples as `name=value, ...`: a PDO of a known mapping, or any frame
    /// once a parameter filter chose its samples.
    joined: bool,
}

impl<'a> Decoded<'a> {
    /// The node id, where the frame has one.
    pub fn node_id(&self) -> Option<u8> {
        match self.message {
            Message::SdoRequest { node, .. }
            | Message::SdoResponse { node, .. }
            | Message::Heartbeat { node, .. }
            | Message::Pdo { node, .. } => Some(node.0),
            Message::Emcy(emcy) => Some(emcy.node.0),
            Message::Nmt { target, .. } => target.map(|n| n.0),
            Message::Sync(_) | Message::Time(_) | Message::Other(_) => None,
        }
    }

    /// The node it is from or for (empty for SYNC; `all` for an NMT command to every node).
    pub fn node(&self) -> impl fmt::Display + use<'_, 'a> {
        fmt_with(move |f| match (self.message, self.node_id()) {
            (Message::Nmt { target: None, .. }, _) => f.write_str("all"),
            (_, Some(node)) => write!(f, "{node}"),
            (_, None) => Ok(()),
        })
    }

    /// `sdo →`, `sdo ←`, `pdo`, `heartbeat`, `emcy`, `nmt`, `sync` or `other`.
    pub fn kind(&self) -> &'static str {
        match self.message {
            Message::SdoRequest { .. } => "sdo →",
            Message::SdoResponse { .. } => "sdo ←",
            Message::Pdo { .. } => "pdo",
            Message::Heartbeat { .. } => "heartbeat",
            Message::Emcy(_) => "emcy",
            Message::Nmt { .. } => "nmt",
            Message::Sync(_) => "sync",
            Message::Time(_) | Message::Other(_) => "other",
        }
    }

    /// The parameter values it carries.
    pub fn samples(&self) -> &[Sample<'a>] {
        &self.samples
    }

    /// The object, PDO or code.
    pub fn what(&self) -> impl fmt::Display + use<'_, 'a> {
        fmt_with(move |f| self.write_what(f))
    }

    /// The value, typed.
    pub fn value(&self) -> impl fmt::Display + use<'_, 'a> {
        fmt_with(move |f| self.write_value(f))
    }

    /// Keeps only the samples of `parameters`, shown as `name=value, ...`; `false` (the frame
    /// is dropped) if none is left.
    pub fn keep_parameters(&mut self, parameters: &BTreeSet<String>) -> bool {
        self.samples.retain(|s| match s.name() {
            Some(name) => parameters.contains(name),
            None => parameters.contains(&s.parameter().to_string()),
        });
        self.joined = true;
        !self.samples.is_empty()
    }

    /// The trigger events of the frame: its samples with a number, then its own event.
    pub fn events(&self) -> impl Iterator<Item = Event<'_>> {
        let node = self.node_id().unwrap_or(0);
        let samples = self.samples.iter().filter_map(move |s| {
            Some(Event::Sample {
                node,
                parameter: s.name()?,
                value: s.value()?,
            })
        });
        samples.chain(self.event())
    }

    /// What a trigger sees of it besides its samples: an EMCY, a node's state, an NMT command.
    fn event(&self) -> Option<Event<'static>> {
        match self.message {
            Message::Heartbeat { node, state } => Some(Event::State {
                node: node.0,
                state: state.code(),
            }),
            Message::Emcy(emcy) => Some(Event::Emcy {
                node: emcy.node.0,
                code: emcy.code,
            }),
            Message::Nmt { target, .. } => Some(Event::NmtCommand {
                node: target.map(|n| n.0),
            }),
            _ => None,
        }
    }

    fn name(&self, index: u16, subindex: u8) -> ObjectName<'a> {
        ObjectName {
            known: self.objects.find(index, subindex),
            index,
            subindex,
        }
    }

    fn write_what(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.message {
            Message::SdoRequest { data, .. } => {
                let (index, subindex) = mux(&data);
                let name = self.name(index, subindex);
                match data[0] >> 5 {
                    1 => write!(f, "write {name}"),
                    2 => write!(f, "read {name}"),
                    4 => write!(f, "abort {name}"),
                    _ => f.write_str("segment"),
                }
            }
            Message::SdoResponse { data, .. } => {
                let (index, subindex) = mux(&data);
                let name = self.name(index, subindex);
                if self.message.expedited_value().is_some() {
                    return write!(f, "{name}");
                }
                match data[0] >> 5 {
                    3 => write!(f, "{name} written"),
                    4 => write!(f, "abort {name}"),
                    _ => f.write_str("segment"),
                }
            }
            Message::Emcy(emcy) => write!(f, "{:#06X}", emcy.code),
            Message::Pdo { kind, number, .. } => write!(f, "{kind:?}{number}"),
            Message::Time(frame) | Message::Other(frame) => write!(f, "{:03X}", frame.id()),
            Message::Heartbeat { .. } | Message::Nmt { .. } | Message::Sync(_) => Ok(()),
        }
    }

    fn write_value(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.joined {
            let mut separator = "";
            for s in &self.samples {
                write!(f, "{separator}{}={}", s.parameter(), s.text())?;
                separator = ", ";
            }
            return Ok(());
        }
        let sample = self.samples.first();
        match self.message {
            Message::SdoRequest { data, .. } => match (sample, data[0] >> 5) {
                (Some(sample), _) => write!(f, "{}", sample.text()),
                (None, 1) => f.write_str("(segmented)"),
                (None, 2) => Ok(()),
                (None, 4) => write_abort(f, &data),
                (None, _) => write!(f, "{data:02X?}"),
            },
            Message::SdoResponse { data, .. } => match (sample, data[0] >> 5) {
                (Some(sample), _) => write!(f, "{}", sample.text()),
                (None, 3) => f.write_str("ok"),
                (None, 4) => write_abort(f, &data),
                (None, _) => write!(f, "{data:02X?}"),
            },
            Message::Heartbeat { state, .. } => write!(f, "{state:?}"),
            Message::Emcy(emcy) => write!(
                f,
                "{} (register {:#04x})",
                self.objects.emcy_name(emcy.code).unwrap_or("unknown code"),
                emcy.register.bits()
            ),
            Message::Nmt { command, .. } => write!(f, "{command:?}"),
            Message::Sync(counter) => write!(f, "{counter:?}"),
            Message::Pdo { frame, .. } => {
                write!(f, "{:02X?} (mapping not in the capture)", frame.data())
            }
            Message::Time(frame) | Message::Other(frame) => write!(f, "{:02X?}", frame.data()),
        }
    }
}

/// Decodes frames in bus order, learning PDO mappings from the SDO writes it sees.
#[derive(Debug)]
pub struct FrameDecoder<'a> {
    objects: &'a Objects<'a>,
    mappings: PdoMappings,
}

impl<'a> FrameDecoder<'a> {
    /// A decoder for a bus of drives whose objects `objects` indexes.
    pub fn new(objects: &'a Objects<'a>) -> Self {
        Self {
            objects,
            mappings: PdoMappings::default(),
        }
    }

    /// The next frame, decoded.
    pub fn decode(&mut self, frame: &CanFrame) -> Decoded<'a> {
        let objects = self.objects;
        let message = Message::classify(frame);
        let mut samples = Samples::new();
        let mut joined = false;
        match message {
            Message::SdoRequest { node, data } => {
                if let Some((index, subindex, value)) = expedited_download(&data) {
                    self.mappings.learn(node.0, index, subindex, value);
                    samples.push(Sample::of(objects, index, subindex, value));
                }
            }
            Message::SdoResponse { .. } => {
                if let Some(v) = message.expedited_value() {
                    let bytes = &v.bytes[..usize::from(v.len)];
                    samples.push(Sample::of(objects, v.index, v.subindex, bytes));
                }
            }
            Message::Pdo {
                kind,
                number,
                node,
                frame,
            } => {
                let pdo = (node.0, kind, number);
                joined = self
                    .mappings
                    .decode(objects, pdo, frame.data(), &mut samples);
            }
            _ => {}
        }
        Decoded {
            objects,
            message,
            samples,
            joined,
        }
    }
}

/// The object and value of an expedited download request.
fn expedited_download(data: &[u8; 8]) -> Option<(u16, u8, &[u8])> {
    if data[0] >> 5 != 1 || data[0] & 0b10 == 0 {
        return None;
    }
    let (index, subindex) = mux(data);
    let len = if data[0] & 1 != 0 {
        4 - ((data[0] >> 2) & 3) as usize
    } else {
        4
    };
    Some((index, subindex, &data[4..4 + len]))
}

fn mux(data: &[u8; 8]) -> (u16, u8) {
    (u16::from_le_bytes([data[1], data[2]]), data[3])
}

fn write_abort(f: &mut fmt::Formatter<'_>, data: &[u8; 8]) -> fmt::Result {
    let code = u32::from_le_bytes([data[4], data[5], data[6], data[7]]);
    write!(f, "{code:#010X} {}", AbortCode::from_u32(code).meaning())
}
