//! One PDO as a DBC message: its identifier on a node, its length and its signals.

use std::fmt::Write as _;

use super::signal::Signal;
use super::text;
use crate::ir::{Device, Direction, Mapping};

/// DBC's name for "no node": the sender of what the drive receives, the receiver of what it
/// sends.
const NO_NODE: &str = "Vector__XXX";
/// The COB-ID bits that are not the identifier: valid (31), no RTR (30), extended frame (29).
const VALID: u32 = 1 << 31;
const NO_RTR: u32 = 1 << 30;
const EXTENDED: u32 = 1 << 29;
/// DBC marks an extended (29-bit) identifier by bit 31 of the message id.
const DBC_EXTENDED: u32 = 1 << 31;

/// A PDO left out, and why.
#[derive(Debug)]
pub struct Skipped {
    pdo: String,
    reason: String,
}

impl Skipped {
    /// `name: reason`.
    pub fn into_text(self) -> String {
        format!("{}: {}", self.pdo, self.reason)
    }
}

/// A PDO as a message.
#[derive(Debug, Clone)]
pub struct Message<'d> {
    /// The PDO.
    pub pdo: &'d Mapping,
    /// DBC message id: the CAN identifier, bit 31 set for an extended one.
    pub id: u32,
    /// Payload length in bytes.
    pub length: u32,
    /// The mapped parameters.
    pub signals: Vec<Signal<'d>>,
}

/// The messages of `device`'s PDOs on `node_id`, and the PDOs that cannot be messages.
pub fn messages(device: &Device, node_id: u8) -> (Vec<Message<'_>>, Vec<Skipped>) {
    let mut messages = Vec::new();
    let mut skipped = Vec::new();
    for (pdo, _) in device.pdos() {
        match Message::of(device, pdo, node_id) {
            Ok(m) => messages.push(m),
            Err(reason) => skipped.push(Skipped {
                pdo: pdo.name.clone(),
                reason,
            }),
        }
    }
    (messages, skipped)
}

impl<'d> Message<'d> {
    fn of(device: &'d Device, pdo: &'d Mapping, node_id: u8) -> Result<Self, String> {
        let id = identifier(pdo, node_id).ok_or(
            "no COB-ID: the description declares none and the PDO number is beyond the \
             predefined connection set (1-4)",
        )?;
        let objects = pdo
            .mapped_objects(device)
            .ok_or("an entry is not a PDO-mappable CANopen object")?;
        let mut signals: Vec<Signal<'d>> = Vec::with_capacity(objects.len());
        let mut start = 0;
        for (name, object) in pdo.entries.iter().zip(&objects) {
            let parameter = device
                .parameter(name)
                .ok_or_else(|| format!("entry `{name}` names no parameter"))?;
            let mut signal = Signal::new(device, parameter, start, u32::from(object.bits));
            let taken = |n: &str| signals.iter().any(|s| s.name == n);
            let base = signal.name.clone();
            let mut copy = 2;
            while taken(&signal.name) {
                signal.name = format!("{base}_{copy}");
                copy += 1;
            }
            start += u32::from(object.bits);
            signals.push(signal);
        }
        let length = start.div_ceil(8);
        if length > 8 {
            return Err(format!("{start} bits do not fit a CAN frame"));
        }
        Ok(Self {
            pdo,
            id,
            length,
            signals,
        })
    }

    /// `BO_ id name: length sender` and its signals.
    pub fn write_definition(&self, out: &mut String, node: &str) {
        let (sender, receivers) = match self.pdo.direction {
            Direction::Tx => (node, NO_NODE),
            Direction::Rx => (NO_NODE, node),
        };
        let _ = writeln!(
            out,
            "\nBO_ {} {}: {} {sender}",
            self.id,
            text::identifier(&self.pdo.name),
            self.length
        );
        for s in &self.signals {
            s.write_definition(out, receivers);
        }
    }

    /// The message's and its signals' comments.
    pub fn write_comments(&self, out: &mut String) {
        let kind = match self.pdo.direction {
            Direction::Tx => "TPDO",
            Direction::Rx => "RPDO",
        };
        let mut about = format!(
            "{kind}{}{}",
            self.pdo.number(),
            self.pdo
                .doc
                .as_deref()
                .map(|d| format!(": {d}"))
                .unwrap_or_default()
        );
        if !self.pdo.enabled {
            about.push_str(
                " (not valid by default, COB-ID bit 31 set: enable it on the drive first)",
            );
        }
        let _ = writeln!(out, "CM_ BO_ {} \"{}\";", self.id, text::string(&about));
        for s in &self.signals {
            s.write_comment(out, self.id);
        }
    }

    /// `SIG_VALTYPE_` lines of the float signals.
    pub fn write_value_types(&self, out: &mut String) {
        for s in &self.signals {
            if let Some(kind) = s.float_type() {
                let _ = writeln!(out, "SIG_VALTYPE_ {} {} : {kind};", self.id, s.name);
            }
        }
    }

    /// `VAL_` lines of the enumerated signals.
    pub fn write_value_tables(&self, out: &mut String) {
        for s in &self.signals {
            s.write_value_table(out, self.id);
        }
    }
}

/// The PDO's CAN identifier on `node_id` as a DBC message id: the declared COB-ID (plus the
/// node id where it says so), else the CiA 301 predefined connection set for PDOs 1-4.
fn identifier(pdo: &Mapping, node_id: u8) -> Option<u32> {
    let declared = pdo.pdo()?.cob_id;
    let (value, plus_node_id) = match declared {
        Some(c) => (c.value, c.plus_node_id),
        None => (predefined(pdo)?, true),
    };
    let base = value & !(VALID | NO_RTR | EXTENDED);
    let can_id = if plus_node_id {
        base + u32::from(node_id)
    } else {
        base
    };
    Some(if value & EXTENDED != 0 {
        can_id | DBC_EXTENDED
    } else {
        can_id
    })
}

/// CiA 301's predefined connection set: TPDO n at 180h + (n-1) × 100h, RPDO n at 200h + ...,
/// for n in 1-4 (before the node id is added).
fn predefined(pdo: &Mapping) -> Option<u32> {
    let number = u32::from(pdo.number());
    let first = match pdo.direction {
        Direction::Tx => 0x180,
        Direction::Rx => 0x200,
    };
    (1..=4)
        .contains(&number)
        .then(|| first + (number - 1) * 0x100)
}
