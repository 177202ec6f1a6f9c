//! The SRDOs of a simulated node, with the same rules as a real consumer and producer (drivebus's
//! sans-I/O SRDO core). Each `[[srdo]]` of the description runs with the communication parameters
//! the drive holds when it enters Operational: a sub-index of 1300h + n the description has as an
//! object is read from the store (a master may have written it), the others are the `[[srdo]]`
//! defaults. Entering Operational needs every described signature (13FFh sub n) to match its
//! configuration and 13FEh to be A5h (SWD manual lines 3568, 3574-3581). While Operational, each
//! TX SRDO is sent every SCT (normal data from the mapped parameters, then the inverted frame);
//! each valid RX SRDO goes through an `SrdoConsumer`, so a parameter changes only for a
//! consistent pair received within SRVT, and every refusal (SCT, SRVT, inconsistent, lone,
//! wrong length) is kept for inspection.
//!
//! Only byte-aligned entries are carried (every SWD mapping is, lines 1745-1934): an SRDO with a
//! bit-sized entry is left out, and [`Srdos::skipped`] names it.

use std::time::Duration;

use drivebus::canopen::srdo::mapping::{data_bits, frame_bytes};
use drivebus::canopen::srdo::{
    signature, SrdoCommunication, SrdoConfig, SrdoConsumer, SrdoDirection, SrdoError, SrdoProducer,
};
use drivebus::canopen::{CanFrame, NodeId};
use drivegen::ir::{Device, Mapping, SrdoDefaults};

use crate::behaviour::object;
use crate::drive::Drive;
use crate::store::{ParamId, Store};

/// One SRDO's normal-data parameters and their byte widths, in payload order.
#[derive(Debug, Clone)]
struct Fields(Vec<(ParamId, usize)>);

impl Fields {
    /// The normal entries of `srdo`, if all are byte-aligned parameters of the store.
    fn of(srdo: &Mapping, device: &Device, store: &Store) -> Option<Self> {
        let objects = srdo.mapped_objects(device)?;
        let fields = srdo
            .entries
            .iter()
            .zip(&objects)
            .step_by(2)
            .map(|(name, object)| {
                (object.bits % 8 == 0).then_some(())?;
                Some((store.id(name)?, usize::from(object.bits / 8)))
            })
            .collect::<Option<Vec<_>>>()?;
        (frame_bytes(&objects) as usize == fields.iter().map(|f| f.1).sum::<usize>())
            .then_some(Self(fields))
    }

    /// The normal data: each parameter's little-endian bytes, cut to its entry's width.
    fn payload(&self, store: &Store) -> Vec<u8> {
        self.0
            .iter()
            .flat_map(|&(id, width)| store.bytes(id).iter().copied().take(width))
            .collect()
    }

    /// Writes released normal data to the parameters, as a client write is checked.
    fn release(&self, drive: &mut Drive, payload: &[u8]) {
        let mut offset = 0;
        for &(id, width) in &self.0 {
            if let Some(bytes) = payload.get(offset..offset + width) {
                // A value the drive refuses (range) is dropped, as the drive would.
                let _ = drive.write(id, bytes);
            }
            offset += width;
        }
    }
}

#[derive(Debug)]
struct Produced {
    producer: SrdoProducer,
    fields: Fields,
}

#[derive(Debug)]
struct Consumed {
    number: u8,
    consumer: SrdoConsumer,
    fields: Fields,
}

/// The SRDOs a simulated node produces and consumes.
#[derive(Debug, Default)]
pub struct Srdos {
    produced: Vec<Produced>,
    consumed: Vec<Consumed>,
    refusals: Vec<(u8, SrdoError)>,
    skipped: Vec<u8>,
}

impl Srdos {
    /// The SRDOs of the drive's description on `node`, as its store configures them now.
    pub fn new(store: &Store, node: NodeId) -> Self {
        let mut srdos = Self::default();
        srdos.configure(store, node);
        srdos
    }

    /// Rebuilds the SRDOs from the configuration the store holds now; refusals are kept.
    pub fn configure(&mut self, store: &Store, node: NodeId) {
        self.produced.clear();
        self.consumed.clear();
        self.skipped.clear();
        let device = store.device();
        for (srdo, defaults) in device.srdos() {
            let Some(communication) = communication(store, srdo, defaults, node) else {
                self.skipped.push(defaults.number);
                continue;
            };
            if communication.direction != SrdoDirection::Invalid
                && !self.add(srdo, defaults.number, communication, device, store)
            {
                self.skipped.push(defaults.number);
            }
        }
    }

    /// Why the node may not enter Operational, if it may not: a described signature (13FFh sub
    /// n) that is not its SRDO's configuration's, or 13FEh not A5h.
    pub fn configuration_error(store: &Store, node: NodeId) -> Option<String> {
        if let Some(valid) = object(store, 0x13FE, 0) {
            let value = store.int(valid);
            if value != Some(0xA5) {
                return Some(format!("13FEh is {value:?}, not A5h"));
            }
        }
        let device = store.device();
        device.srdos().find_map(|(srdo, defaults)| {
            let stored = store.int(object(store, 0x13FF, defaults.number)?)?;
            let mapping = srdo.mapped_objects(device)?;
            let config = SrdoConfig {
                number: defaults.number,
                communication: communication(store, srdo, defaults, node)?,
                mapping: &mapping,
            };
            let computed = signature(&config).ok()?;
            (i128::from(computed) != stored).then(|| {
                format!(
                    "SRDO {} signature: 13FFh holds {stored:#06X}, the configuration gives {computed:#06X}",
                    defaults.number
                )
            })
        })
    }

    /// Adds one SRDO; false if the simulator cannot carry it.
    fn add(
        &mut self,
        srdo: &Mapping,
        number: u8,
        communication: SrdoCommunication,
        device: &Device,
        store: &Store,
    ) -> bool {
        let (Some(fields), Some(objects)) =
            (Fields::of(srdo, device, store), srdo.mapped_objects(device))
        else {
            return false;
        };
        let (Ok(ids), Ok(timing)) = (communication.cob_ids(), communication.timing()) else {
            return false;
        };
        let bits = data_bits(&objects);
        match communication.direction {
            SrdoDirection::Transmit => match SrdoProducer::new(ids, timing.sct(), bits) {
                Ok(producer) => self.produced.push(Produced { producer, fields }),
                Err(_) => return false,
            },
            SrdoDirection::Receive => match SrdoConsumer::new(ids, timing, bits) {
                Ok(consumer) => self.consumed.push(Consumed {
                    number,
                    consumer,
                    fields,
                }),
                Err(_) => return false,
            },
            SrdoDirection::Invalid => {}
        }
        true
    }

    /// The node entered Operational at `now`: SCT monitoring of every RX SRDO starts.
    pub fn start(&mut self, now: Duration) {
        for c in &mut self.consumed {
            c.consumer.start(now);
        }
    }

    /// Handles a received frame; true if it was an RX SRDO frame (released or refused).
    pub fn handle(&mut self, frame: &CanFrame, now: Duration, drive: &mut Drive) -> bool {
        for c in &mut self.consumed {
            match c.consumer.handle(frame, now) {
                None => continue,
                Some(Ok(Some(payload))) => c.fields.release(drive, payload.as_bytes()),
                Some(Ok(None)) => {}
                Some(Err(e)) => self.refusals.push((c.number, e)),
            }
            return true;
        }
        false
    }

    /// The TX SRDO pairs due at `now`, and SRVT / SCT expiries of the RX SRDOs.
    pub fn poll(&mut self, now: Duration, store: &Store) -> Vec<CanFrame> {
        for c in &mut self.consumed {
            if let Err(e) = c.consumer.poll(now) {
                self.refusals.push((c.number, e));
            }
        }
        self.produced
            .iter_mut()
            .filter_map(|p| {
                p.producer
                    .poll(now, &p.fields.payload(store))
                    .ok()
                    .flatten()
            })
            .flatten()
            .collect()
    }

    /// Every refusal so far: SRDO number and why.
    pub fn refusals(&self) -> &[(u8, SrdoError)] {
        &self.refusals
    }

    /// Valid SRDOs the simulator cannot carry (bit-sized entries, unusable COB-IDs or times).
    pub fn skipped(&self) -> &[u8] {
        &self.skipped
    }
}

/// SRDO `srdo`'s communication parameters as the drive holds them: each sub-index from its object
/// when the description has one, else the `[[srdo]]` default. `None` if the COB-IDs depend on
/// the node-ID beyond 11 bits or a held value does not fit.
fn communication(
    store: &Store,
    srdo: &Mapping,
    defaults: &SrdoDefaults,
    node: NodeId,
) -> Option<SrdoCommunication> {
    let index = 0x1300 + u16::from(defaults.number);
    let held = |sub: u8, default: i128| -> Option<i128> {
        match object(store, index, sub) {
            Some(id) => store.int(id),
            None => Some(default),
        }
    };
    let [normal, inverted] = defaults.cob_ids.map(|c| c.resolve(Some(node.0)));
    Some(SrdoCommunication {
        direction: SrdoDirection::from_u8(
            u8::try_from(held(1, srdo.information_direction().into())?).ok()?,
        )?,
        sct_ms: u16::try_from(held(2, defaults.sct_ms.into())?).ok()?,
        srvt_ms: u16::try_from(held(3, defaults.srvt_ms.into())?).ok()?,
        transmission_type: u8::try_from(held(4, srdo.transmission_type.unwrap_or(0xFE).into())?)
            .ok()?,
        cob_id_normal: u32::try_from(held(5, normal?.into())?).ok()?,
        cob_id_inverted: u32::try_from(held(6, inverted?.into())?).ok()?,
    })
}
