//! A CANopen frame as people and tools read it: named, typed, with the parameter values it
//! carries. `decode` prints these; `trace` filters and triggers on them.

use drivebus::canopen::message::Message;
use drivebus::canopen::sdo::AbortCode;
use drivebus::canopen::CanFrame;
use drivebus::interpret::Shown;
use drivebus::trace::Event;
use drivegen::ir::{Device, Parameter};

use crate::objects::Objects;
use crate::pdo_mappings::PdoMappings;

/// A parameter value a frame carries.
#[derive(Debug, Clone, PartialEq)]
pub struct Sample {
    /// The parameter's name, or `INDEX:SUB` for an object the description does not have.
    pub parameter: String,
    /// The value for people, with its unit or names.
    pub text: String,
    /// The value as a number (an enumeration or flags word by its raw value), if it is one.
    pub value: Option<f64>,
}

impl Sample {
    pub(crate) fn of(parameter: &Parameter, shown: Shown) -> Self {
        let value = crate::series::number(&shown);
        Self {
            parameter: parameter.name.clone(),
            text: shown.text,
            value,
        }
    }

    pub(crate) fn unknown(index: u16, subindex: u8, bytes: &[u8]) -> Self {
        Self {
            parameter: format!("{index:04X}:{subindex:02X}"),
            text: format!("{bytes:02X?}"),
            value: None,
        }
    }
}

/// One decoded frame.
#[derive(Debug, Clone)]
pub struct Decoded {
    /// The node it is from or for (empty for SYNC; `all` for an NMT command to every node).
    pub node: String,
    /// `sdo →`, `sdo ←`, `pdo`, `heartbeat`, `emcy`, `nmt`, `sync` or `other`.
    pub kind: &'static str,
    /// The object, PDO or code.
    pub what: String,
    /// The value, typed.
    pub value: String,
    /// The parameter values it carries.
    pub samples: Vec<Sample>,
    /// What a trigger sees of it besides its samples: an EMCY, a node's state, an NMT command.
    pub event: Option<Event<'static>>,
    /// The node id, where the frame has one.
    pub node_id: Option<u8>,
}

impl Decoded {
    /// The trigger events of the frame: its samples with a number, then its own event.
    pub fn events(&self) -> impl Iterator<Item = Event<'_>> {
        let node = self.node_id.unwrap_or(0);
        let samples = self.samples.iter().filter_map(move |s| {
            Some(Event::Sample {
                node,
                parameter: &s.parameter,
                value: s.value?,
            })
        });
        samples.chain(self.event)
    }
}

/// Decodes frames in bus order, learning PDO mappings from the SDO writes it sees.
#[derive(Debug)]
pub struct FrameDecoder<'d> {
    objects: Objects<'d>,
    mappings: PdoMappings,
}

impl<'d> FrameDecoder<'d> {
    /// A decoder for a bus of drives `device` describes.
    pub fn new(device: &'d Device) -> Self {
        Self {
            objects: Objects::new(device),
            mappings: PdoMappings::default(),
        }
    }

    /// The next frame, decoded.
    pub fn decode(&mut self, frame: &CanFrame) -> Decoded {
        let message = Message::classify(frame);
        if let Message::SdoRequest { node, data } = message {
            if let Some((index, subindex, value)) = expedited_download(&data) {
                self.mappings.learn(node.0, index, subindex, value);
            }
        }
        self.describe(message)
    }

    fn describe(&self, message: Message) -> Decoded {
        let objects = &self.objects;
        let line = |node: Option<u8>, kind, what: String, value: String| Decoded {
            node: node.map_or(String::new(), |n| n.to_string()),
            kind,
            what,
            value,
            samples: Vec::new(),
            event: None,
            node_id: node,
        };
        match message {
            Message::SdoRequest { node, data } => {
                let (what, value, sample) = sdo_request(objects, &data);
                Decoded {
                    samples: sample.into_iter().collect(),
                    ..line(Some(node.0), "sdo →", what, value)
                }
            }
            Message::SdoResponse { node, data } => {
                let (what, value, sample) = sdo_response(objects, &message, &data);
                Decoded {
                    samples: sample.into_iter().collect(),
                    ..line(Some(node.0), "sdo ←", what, value)
                }
            }
            Message::Heartbeat { node, state } => Decoded {
                event: Some(Event::State {
                    node: node.0,
                    state: state.code(),
                }),
                ..line(
                    Some(node.0),
                    "heartbeat",
                    String::new(),
                    format!("{state:?}"),
                )
            },
            Message::Emcy(emcy) => Decoded {
                event: Some(Event::Emcy {
                    node: emcy.node.0,
                    code: emcy.code,
                }),
                ..line(
                    Some(emcy.node.0),
                    "emcy",
                    format!("{:#06X}", emcy.code),
                    format!(
                        "{} (register {:#04x})",
                        objects.emcy_name(emcy.code).unwrap_or("unknown code"),
                        emcy.register.bits()
                    ),
                )
            },
            Message::Nmt { command, target } => Decoded {
                node: target.map_or("all".into(), |n| n.0.to_string()),
                event: Some(Event::NmtCommand {
                    node: target.map(|n| n.0),
                }),
                ..line(
                    target.map(|n| n.0),
                    "nmt",
                    String::new(),
                    format!("{command:?}"),
                )
            },
            Message::Sync(counter) => line(None, "sync", String::new(), format!("{counter:?}")),
            Message::Pdo {
                kind,
                number,
                node,
                frame,
            } => {
                let what = format!("{kind:?}{number}");
                match self
                    .mappings
                    .decode(objects, node.0, kind, number, frame.data())
                {
                    Some(samples) => Decoded {
                        samples,
                        ..line(Some(node.0), "pdo", what, String::new())
                    }
                    .with_joined_value(),
                    None => line(
                        Some(node.0),
                        "pdo",
                        what,
                        format!("{:02X?} (mapping not in the capture)", frame.data()),
                    ),
                }
            }
            Message::Time(frame) | Message::Other(frame) => line(
                None,
                "other",
                format!("{:03X}", frame.id()),
                format!("{:02X?}", frame.data()),
            ),
        }
    }
}

impl Decoded {
    /// The value as `name=value, ...` of its samples.
    fn with_joined_value(mut self) -> Self {
        let pairs: Vec<String> = self
            .samples
            .iter()
            .map(|s| format!("{}={}", s.parameter, s.text))
            .collect();
        self.value = pairs.join(", ");
        self
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

fn sdo_request(objects: &Objects<'_>, data: &[u8; 8]) -> (String, String, Option<Sample>) {
    let (index, subindex) = mux(data);
    let name = objects.name(index, subindex);
    if let Some((index, subindex, bytes)) = expedited_download(data) {
        let sample = objects.sample(index, subindex, bytes);
        return (format!("write {name}"), sample.text.clone(), Some(sample));
    }
    let (what, value) = match data[0] >> 5 {
        1 => (format!("write {name}"), "(segmented)".into()),
        2 => (format!("read {name}"), String::new()),
        4 => (format!("abort {name}"), abort(data)),
        _ => ("segment".into(), format!("{data:02X?}")),
    };
    (what, value, None)
}

fn sdo_response(
    objects: &Objects<'_>,
    message: &Message,
    data: &[u8; 8],
) -> (String, String, Option<Sample>) {
    if let Some(v) = message.expedited_value() {
        let sample = objects.sample(v.index, v.subindex, &v.bytes[..v.len as usize]);
        return (
            objects.name(v.index, v.subindex),
            sample.text.clone(),
            Some(sample),
        );
    }
    let (index, subindex) = mux(data);
    let name = objects.name(index, subindex);
    let (what, value) = match data[0] >> 5 {
        3 => (format!("{name} written"), "ok".into()),
        4 => (format!("abort {name}"), abort(data)),
        _ => ("segment".into(), format!("{data:02X?}")),
    };
    (what, value, None)
}

fn abort(data: &[u8; 8]) -> String {
    let code = u32::from_le_bytes([data[4], data[5], data[6], data[7]]);
    format!("{code:#010X} {}", AbortCode::from_u32(code).meaning())
}
