//! What `watch --pdo` maps, and where: the watched parameters as TPDO entries (each refused
//! with its reason before anything is written), and the TPDO that carries them: one of the
//! drive's TPDOs that already does, else one of the described TPDOs reprogrammed for the watch.

use drivebus::canopen::pdo::{MappedObject, COB_ID_INVALID};
use drivebus::canopen::NodeId;
use drivegen::ir::{Device, Direction, Parameter, Pdo};

use super::tpdo_config::TpdoConfig;

/// The most bytes one PDO carries.
const PDO_BYTES: usize = 8;
/// The most bits a CAN identifier of the base frame format has.
const BASE_ID: u32 = 0x7FF;

/// How the drive is to send the TPDO.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Trigger {
    /// At every SYNC (transmission type 1); the watch sends SYNC at the interval.
    Sync,
    /// By the drive's event timer (transmission type 254), every so many ms.
    EventTimer(u16),
}

/// The TPDO a node's watch reads.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Choice {
    /// The TPDO as the watch needs it.
    pub watched: TpdoConfig,
    /// The configuration to write back at the end; `None` when the drive's own TPDO serves
    /// as it is (nothing is written).
    pub saved: Option<TpdoConfig>,
    /// Each watched parameter's byte offset in the payload.
    pub offsets: Vec<usize>,
}

impl Choice {
    /// The TPDO's CAN identifier.
    pub fn can_id(&self) -> u16 {
        (self.watched.cob_id & BASE_ID) as u16
    }

    /// The payload bytes the TPDO's mapping takes (bit-packed entries of a drive's own TPDO
    /// included, rounded up), so every watched parameter's bytes lie within a payload this long.
    pub fn payload_len(&self) -> usize {
        let bits: usize = self
            .watched
            .entries
            .iter()
            .map(|e| usize::from(e.bits))
            .sum();
        bits.div_ceil(8)
    }
}

/// The TPDO entries of `parameters`, or every refusal, each naming the parameter and why.
pub fn entries(parameters: &[&Parameter]) -> Result<Vec<MappedObject>, Vec<String>> {
    let mut refused = Vec::new();
    let mut entries = Vec::new();
    for parameter in parameters {
        match entry(parameter) {
            Ok(e) => entries.push(e),
            Err(why) => refused.push(format!("{}: {why}", parameter.name)),
        }
    }
    let bytes: usize = entries.iter().map(|e| usize::from(e.bits) / 8).sum();
    if refused.is_empty() && bytes > PDO_BYTES {
        refused.push(format!(
            "the parameters take {bytes} bytes together; a PDO carries {PDO_BYTES}: watch fewer"
        ));
    }
    match refused.is_empty() {
        true => Ok(entries),
        false => Err(refused),
    }
}

/// One parameter's TPDO entry, or why it has none.
fn entry(parameter: &Parameter) -> Result<MappedObject, String> {
    let Some(object) = parameter.pdo_object() else {
        return Err(match parameter.canopen.is_empty() {
            true => "it has no CANopen object".into(),
            false => "its CANopen object depends on the variant".into(),
        });
    };
    let at = format!("{:04X}h:{:02X}h", object.index, object.subindex);
    if !matches!(object.pdo, Pdo::Tx | Pdo::Both) {
        let declared = match object.pdo {
            Pdo::Rx => "into RPDOs only",
            _ => "into no PDO",
        };
        return Err(format!("the description lets {at} be mapped {declared}"));
    }
    let bits = drivegen::ir::pdo_bits(parameter.data_type);
    if bits % 8 != 0 || bits == 0 || bits > 64 {
        return Err(format!(
            "{at} is {bits} bits; the watch maps whole bytes, up to 8"
        ));
    }
    Ok(MappedObject::new(object.index, object.subindex, bits as u8))
}

/// The TPDOs the description declares, by number.
pub fn described_tpdos(device: &Device) -> Vec<u16> {
    let mut numbers: Vec<u16> = device
        .pdos()
        .filter(|(m, _)| m.direction == Direction::Tx)
        .map(|(_, p)| p.number)
        .collect();
    numbers.sort_unstable();
    numbers.dedup();
    numbers
}

/// The TPDO of `node` to watch `entries` on, among its TPDOs as they are now (`held`): one that
/// already sends them as `trigger` wants, else the last not valid one that can be set so, else
/// the last one that can, reprogrammed; never one on a CAN identifier in `taken` (the other
/// watched nodes' TPDOs: a drive whose TPDO identifiers do not follow its node id sends on
/// the same identifier as its twin). `Err` says why none can.
pub fn choose(
    held: &[TpdoConfig],
    entries: &[MappedObject],
    trigger: Trigger,
    node: NodeId,
    taken: &[u16],
) -> Result<Choice, String> {
    let free = |choice: &Choice| !taken.contains(&choice.can_id());
    let mut reused = held.iter().filter_map(|t| reuse(t, entries, trigger));
    if let Some(choice) = reused.find(free) {
        return Ok(choice);
    }
    let unused = held.iter().rev().filter(|t| !t.is_valid());
    let used = held.iter().rev().filter(|t| t.is_valid());
    let mut why = String::from("the description declares no TPDO to map into");
    for target in unused.chain(used) {
        match reprogram(target, entries, trigger, node) {
            Ok(choice) if free(&choice) => return Ok(choice),
            Ok(choice) => {
                why = format!(
                    "TPDO {} would go out on CAN id {:03X}h, which another watched node uses",
                    target.number,
                    choice.can_id()
                )
            }
            Err(reason) => why = reason,
        }
    }
    Err(why)
}

/// `target` set to send `entries` as `trigger` wants, or why it cannot be.
fn reprogram(
    target: &TpdoConfig,
    entries: &[MappedObject],
    trigger: Trigger,
    node: NodeId,
) -> Result<Choice, String> {
    let can_id = match target.cob_id & BASE_ID {
        // No identifier assigned: the predefined connection set's, for TPDOs 1-4.
        0 if target.number <= 4 => 0x180 + 0x100 * u32::from(target.number - 1) + u32::from(node.0),
        0 => return Err(format!("TPDO {} has no CAN identifier", target.number)),
        id => id,
    };
    let (transmission_type, event_timer) = match trigger {
        Trigger::Sync if target.transmission_type.is_some() => (1, target.event_timer.map(|_| 0)),
        Trigger::Sync => {
            return Err(format!(
                "TPDO {} has no transmission type (sub-index 2) to set to SYNC",
                target.number
            ))
        }
        Trigger::EventTimer(ms) if target.event_timer.is_some() => (254, Some(ms)),
        Trigger::EventTimer(_) => {
            return Err(format!(
                "TPDO {} has no event timer (sub-index 5): watch on SYNC instead",
                target.number
            ))
        }
    };
    let watched = TpdoConfig {
        number: target.number,
        // Bit 30 (no RTR) is kept as the drive holds it.
        cob_id: (target.cob_id & !COB_ID_INVALID & !BASE_ID) | can_id,
        transmission_type: Some(transmission_type),
        inhibit_time: target.inhibit_time.map(|_| 0),
        event_timer,
        entries: entries.to_vec(),
        beyond: Vec::new(),
    };
    let offsets = watched
        .offsets(entries)
        .ok_or("entries are not whole bytes")?;
    Ok(Choice {
        watched,
        saved: Some(target.clone()),
        offsets,
    })
}

/// `held` as it is, if it is valid, maps every entry and is sent as `trigger` wants.
fn reuse(held: &TpdoConfig, entries: &[MappedObject], trigger: Trigger) -> Option<Choice> {
    // Without sub-index 2 a TPDO is event-driven (type 255, the CiA 301 default).
    let transmission_type = held.transmission_type.unwrap_or(255);
    let sent = match trigger {
        // Every SYNC: a sample per SYNC (types 2-240 would skip SYNCs).
        Trigger::Sync => transmission_type == 1,
        Trigger::EventTimer(_) => {
            transmission_type >= 254 && held.event_timer.is_some_and(|t| t > 0)
        }
    };
    if !held.is_valid() || !sent {
        return None;
    }
    Some(Choice {
        offsets: held.offsets(entries)?,
        watched: held.clone(),
        saved: None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const STATUSWORD: MappedObject = MappedObject::new(0x6041, 0, 16);
    const VELOCITY: MappedObject = MappedObject::new(0x606C, 0, 32);

    fn tpdo(number: u16, cob_id: u32, entries: Vec<MappedObject>) -> TpdoConfig {
        TpdoConfig {
            number,
            cob_id,
            transmission_type: Some(1),
            inhibit_time: Some(0),
            event_timer: Some(0),
            entries,
            beyond: Vec::new(),
        }
    }

    #[test]
    fn a_tpdo_that_already_carries_the_parameters_is_used_as_it_is() {
        let held = [
            tpdo(1, 0x181, vec![STATUSWORD]),
            tpdo(3, 0x381, vec![STATUSWORD, VELOCITY]),
        ];
        let choice = choose(&held, &[VELOCITY], Trigger::Sync, NodeId(1), &[]).unwrap();
        assert_eq!(
            (choice.watched.number, choice.saved, choice.offsets),
            (3, None, vec![2])
        );
        // On an identifier another node's TPDO uses: TPDO 1 (the last one) is reprogrammed.
        let twin = choose(&held, &[VELOCITY], Trigger::Sync, NodeId(1), &[0x381]).unwrap();
        assert_eq!((twin.watched.number, twin.can_id()), (1, 0x181));
        let both = [0x381, 0x181];
        let why = choose(&held, &[VELOCITY], Trigger::Sync, NodeId(1), &both).unwrap_err();
        assert!(why.contains("another watched node"), "{why}");
    }

    #[test]
    fn otherwise_the_last_unused_tpdo_is_reprogrammed_and_saved() {
        let unused = tpdo(2, 0x8000_0281, vec![]);
        let held = [
            tpdo(1, 0x181, vec![STATUSWORD]),
            unused.clone(),
            tpdo(3, 0x381, vec![]),
        ];
        let choice = choose(
            &held,
            &[VELOCITY, STATUSWORD],
            Trigger::EventTimer(5),
            NodeId(1),
            &[],
        )
        .unwrap();
        assert_eq!(choice.saved, Some(unused));
        assert_eq!(choice.watched.cob_id, 0x281);
        assert_eq!(choice.watched.transmission_type, Some(254));
        assert_eq!(choice.watched.event_timer, Some(5));
        assert_eq!(choice.offsets, [0, 4]);
        assert_eq!(choice.payload_len(), 6);
    }

    #[test]
    fn a_bit_packed_tpdo_needs_its_whole_payload() {
        let flags = [
            MappedObject::new(0x2000, 1, 1),
            MappedObject::new(0x2000, 2, 7),
        ];
        let held = [tpdo(1, 0x181, [&flags[..], &[STATUSWORD]].concat())];
        let choice = choose(&held, &[STATUSWORD], Trigger::Sync, NodeId(1), &[]).unwrap();
        assert_eq!((choice.payload_len(), choice.offsets), (3, vec![1]));
    }

    #[test]
    fn no_tpdo_or_no_event_timer_is_a_reason() {
        assert!(choose(&[], &[VELOCITY], Trigger::Sync, NodeId(1), &[]).is_err());
        let mut held = tpdo(1, 0x181, vec![]);
        held.event_timer = None;
        let why = choose(&[held], &[VELOCITY], Trigger::EventTimer(5), NodeId(1), &[]).unwrap_err();
        assert!(why.contains("no event timer"), "{why}");
    }
}
