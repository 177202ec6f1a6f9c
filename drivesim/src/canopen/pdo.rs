//! The PDOs of a simulated node (CiA 301 §7.2.2): while Operational, each valid TPDO is sent with
//! the live values of its mapped parameters as its transmission type says, and each valid RPDO
//! writes its payload to the mapped parameters through the drive's checks (so a controlword in
//! an RPDO moves the state machine as an SDO write would).
//!
//! The configuration is read from the communication (1400h / 1800h + n − 1) and mapping (1600h /
//! 1A00h + n − 1) objects the store holds when the node enters Operational, so a master's SDO
//! configuration takes effect then, as on a drive. Transmission types: 0 (acyclic synchronous:
//! at a SYNC after a change), 1-240 (every n-th SYNC), 254 / 255 (on change, no more often than
//! the inhibit time, and every event-timer period). An RPDO of type 0-240 takes effect at the
//! next SYNC, of type 254 / 255 at once. Not carried, and named in [`Pdos::skipped`]: RTR-only
//! types 252 / 253, 29-bit identifiers, entries that are not whole bytes or name no parameter.

use std::time::Duration;

use drivebus::canopen::frame::cob;
use drivebus::canopen::pdo::MappedObject;
use drivebus::canopen::CanFrame;

use crate::behaviour::object;
use crate::drive::Drive;
use crate::store::{ParamId, Store};

/// COB-ID bit 31: the PDO is not valid.
const NOT_VALID: i128 = 1 << 31;
/// COB-ID bit 29: a 29-bit identifier.
const EXTENDED: i128 = 1 << 29;
/// Highest transmission type counted in SYNCs.
const MAX_SYNC_PERIOD: u8 = 240;
/// Inhibit time unit (communication sub-index 3): 100 µs.
const INHIBIT_UNIT: Duration = Duration::from_micros(100);

/// A PDO's mapped parameters and their byte widths, in payload order.
#[derive(Debug, Clone)]
struct Fields(Vec<(ParamId, usize)>);

impl Fields {
    /// The entries of mapping object `index` as the store holds it.
    fn held(store: &Store, index: u16) -> Result<Self, String> {
        let count = held_int(store, index, 0).ok_or("no mapping object")?;
        let mut fields = Vec::new();
        for sub in 1..=u8::try_from(count).map_err(|_| "entry count above 255")? {
            let entry = held_int(store, index, sub).ok_or(format!("no entry {sub}"))?;
            let mapped = MappedObject::from_entry(entry as u32);
            if mapped.bits % 8 != 0 {
                return Err(format!(
                    "entry {sub} is {} bits, not whole bytes",
                    mapped.bits
                ));
            }
            let id = object(store, mapped.index, mapped.subindex).ok_or(format!(
                "entry {sub} maps {:04X}h:{:02X}h, which the drive does not have",
                mapped.index, mapped.subindex
            ))?;
            fields.push((id, usize::from(mapped.bits / 8)));
        }
        if fields.iter().map(|f| f.1).sum::<usize>() > 8 {
            return Err("maps more than 8 bytes".into());
        }
        Ok(Self(fields))
    }

    fn len(&self) -> usize {
        self.0.iter().map(|f| f.1).sum()
    }

    /// Each parameter's little-endian bytes, cut to its entry's width.
    fn payload(&self, store: &Store) -> Vec<u8> {
        let mut out = Vec::with_capacity(self.len());
        for &(id, width) in &self.0 {
            let bytes = store.bytes(id);
            out.extend((0..width).map(|i| bytes.get(i).copied().unwrap_or(0)));
        }
        out
    }

    /// Writes a received payload to the parameters, each checked as a client write is.
    fn write(&self, drive: &mut Drive, payload: &[u8]) {
        let mut offset = 0;
        for &(id, width) in &self.0 {
            let mut bytes = payload[offset..offset + width].to_vec();
            // An entry narrower than its parameter carries the low bytes.
            bytes.resize(drive.store().bytes(id).len().max(width), 0);
            // A value the drive refuses (range, access) is dropped, as the drive would.
            let _ = drive.write(id, &bytes);
            offset += width;
        }
    }
}

/// When a TPDO is sent.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Trigger {
    /// Type 0: at a SYNC, if the data changed since the last one sent.
    SyncOnChange,
    /// Types 1-240: every n-th SYNC.
    EverySync(u8),
    /// Types 254 / 255: on change, and every event-timer period.
    Event,
}

#[derive(Debug)]
struct Tpdo {
    cob_id: u16,
    trigger: Trigger,
    inhibit: Duration,
    event_timer: Option<Duration>,
    fields: Fields,
    syncs: u8,
    last: Option<(Duration, Vec<u8>)>,
}

impl Tpdo {
    fn frame(&mut self, now: Duration, payload: Vec<u8>) -> Option<CanFrame> {
        let frame = CanFrame::new(self.cob_id, &payload).ok();
        self.last = Some((now, payload));
        frame
    }

    fn changed(&self, payload: &[u8]) -> bool {
        self.last.as_ref().is_none_or(|(_, sent)| sent != payload)
    }

    /// Its frame at a SYNC, if due.
    fn on_sync(&mut self, now: Duration, store: &Store) -> Option<CanFrame> {
        let payload = self.fields.payload(store);
        match self.trigger {
            Trigger::SyncOnChange if self.changed(&payload) => self.frame(now, payload),
            Trigger::EverySync(n) => {
                self.syncs += 1;
                (self.syncs >= n).then(|| {
                    self.syncs = 0;
                    self.frame(now, payload)
                })?
            }
            _ => None,
        }
    }

    /// Its frame at `now` for an event-driven TPDO, if due: a change past the inhibit time, or
    /// the event timer.
    fn on_time(&mut self, now: Duration, store: &Store) -> Option<CanFrame> {
        if self.trigger != Trigger::Event {
            return None;
        }
        let payload = self.fields.payload(store);
        let due = match &self.last {
            None => true,
            Some((at, sent)) => {
                (sent != &payload && now >= *at + self.inhibit)
                    || self.event_timer.is_some_and(|t| now >= *at + t)
            }
        };
        due.then(|| self.frame(now, payload))?
    }
}

#[derive(Debug)]
struct Rpdo {
    cob_id: u16,
    at_sync: bool,
    fields: Fields,
    pending: Option<Vec<u8>>,
}

/// The PDOs a simulated node sends and receives.
#[derive(Debug, Default)]
pub struct Pdos {
    transmit: Vec<Tpdo>,
    receive: Vec<Rpdo>,
    skipped: Vec<String>,
    length_errors: usize,
}

impl Pdos {
    /// Rebuilds the PDOs from the configuration the store holds now (at entering Operational).
    pub fn configure(&mut self, store: &Store) {
        *self = Self {
            length_errors: self.length_errors,
            ..Self::default()
        };
        for n in 0..512u16 {
            self.add_transmit(store, n);
            self.add_receive(store, n);
        }
    }

    fn add_transmit(&mut self, store: &Store, n: u16) {
        let tpdo = match Communication::held(store, 0x1800 + n) {
            None | Some(Ok(None)) => return,
            Some(Err(reason)) => Err(reason),
            Some(Ok(Some(c))) => c.tpdo(store, 0x1A00 + n),
        };
        match tpdo {
            Ok(t) => self.transmit.push(t),
            Err(reason) => self.skipped.push(format!("TPDO {}: {reason}", n + 1)),
        }
    }

    fn add_receive(&mut self, store: &Store, n: u16) {
        let rpdo = match Communication::held(store, 0x1400 + n) {
            None | Some(Ok(None)) => return,
            Some(Err(reason)) => Err(reason),
            Some(Ok(Some(c))) => c.rpdo(store, 0x1600 + n),
        };
        match rpdo {
            Ok(r) => self.receive.push(r),
            Err(reason) => self.skipped.push(format!("RPDO {}: {reason}", n + 1)),
        }
    }

    /// Handles a received frame while Operational: a SYNC (returns the TPDOs it triggers) or an
    /// RPDO. `None` if the frame is neither.
    pub fn handle(
        &mut self,
        frame: &CanFrame,
        now: Duration,
        drive: &mut Drive,
    ) -> Option<Vec<CanFrame>> {
        if frame.id() == cob::SYNC {
            for r in &mut self.receive {
                if let Some(payload) = r.pending.take() {
                    r.fields.write(drive, &payload);
                }
            }
            let store = drive.store();
            return Some(
                self.transmit
                    .iter_mut()
                    .filter_map(|t| t.on_sync(now, store))
                    .collect(),
            );
        }
        let rpdo = self.receive.iter_mut().find(|r| r.cob_id == frame.id())?;
        let data = frame.data();
        if data.len() < rpdo.fields.len() {
            // CiA 301: a PDO shorter than its mapping is not processed.
            self.length_errors += 1;
        } else if rpdo.at_sync {
            rpdo.pending = Some(data.to_vec());
        } else {
            rpdo.fields.write(drive, data);
        }
        Some(Vec::new())
    }

    /// The event-driven TPDOs due at `now`.
    pub fn poll(&mut self, now: Duration, store: &Store) -> Vec<CanFrame> {
        self.transmit
            .iter_mut()
            .filter_map(|t| t.on_time(now, store))
            .collect()
    }

    /// Valid PDOs the simulator cannot carry, each with the reason.
    pub fn skipped(&self) -> &[String] {
        &self.skipped
    }

    /// RPDOs received shorter than their mapping (not processed).
    pub fn length_errors(&self) -> usize {
        self.length_errors
    }
}

/// A PDO's communication parameters as the store holds them.
struct Communication {
    cob_id: u16,
    transmission_type: u8,
    inhibit_time: u16,
    event_timer: u16,
}

impl Communication {
    /// `None` when the drive has no such PDO; `Ok(None)` when it is not valid; an error when
    /// the simulator cannot carry it.
    fn held(store: &Store, index: u16) -> Option<Result<Option<Self>, String>> {
        let cob_id = held_int(store, index, 1)?;
        if cob_id & NOT_VALID != 0 {
            return Some(Ok(None));
        }
        if cob_id & EXTENDED != 0 {
            return Some(Err("29-bit identifiers are not simulated".into()));
        }
        let narrow = |sub: u8, default: u16| {
            held_int(store, index, sub).map_or(default, |v| u16::try_from(v).unwrap_or(default))
        };
        Some(Ok(Some(Self {
            cob_id: (cob_id & 0x7FF) as u16,
            transmission_type: u8::try_from(narrow(2, 255)).unwrap_or(255),
            inhibit_time: narrow(3, 0),
            event_timer: narrow(5, 0),
        })))
    }
}

impl Communication {
    fn tpdo(&self, store: &Store, mapping: u16) -> Result<Tpdo, String> {
        let trigger = match self.transmission_type {
            0 => Trigger::SyncOnChange,
            t @ 1..=MAX_SYNC_PERIOD => Trigger::EverySync(t),
            254 | 255 => Trigger::Event,
            t => return Err(format!("transmission type {t} (RTR only) is not simulated")),
        };
        Ok(Tpdo {
            cob_id: self.cob_id,
            trigger,
            inhibit: INHIBIT_UNIT * u32::from(self.inhibit_time),
            event_timer: (self.event_timer > 0)
                .then(|| Duration::from_millis(u64::from(self.event_timer))),
            fields: Fields::held(store, mapping)?,
            syncs: 0,
            last: None,
        })
    }

    fn rpdo(&self, store: &Store, mapping: u16) -> Result<Rpdo, String> {
        Ok(Rpdo {
            cob_id: self.cob_id,
            at_sync: self.transmission_type <= MAX_SYNC_PERIOD,
            fields: Fields::held(store, mapping)?,
            pending: None,
        })
    }
}

fn held_int(store: &Store, index: u16, sub: u8) -> Option<i128> {
    store.int(object(store, index, sub)?)
}
