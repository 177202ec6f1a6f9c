//! The SRDOs of a simulated node, from the description's `[[srdo]]` defaults, with the same rules
//! as a real consumer and producer (drivebus's sans-I/O SRDO core): while Operational, each valid
//! TX SRDO is sent every SCT (normal data from the mapped parameters, then the inverted frame);
//! each valid RX SRDO goes through an `SrdoConsumer`, so a parameter changes only for a
//! consistent pair received within SRVT, and every refusal (SCT, SRVT, inconsistent, lone,
//! wrong length) is kept for inspection.
//!
//! Only byte-aligned entries are carried (every SWD mapping is, lines 1745-1934): an SRDO with a
//! bit-sized entry is left out, and [`Srdos::skipped`] names it.

use std::time::Duration;

use drivebus::canopen::srdo::mapping::{data_bits, frame_bytes};
use drivebus::canopen::srdo::{SrdoConsumer, SrdoError, SrdoProducer};
use drivebus::canopen::{CanFrame, NodeId};
use drivegen::ir::{Device, PdoDirection, SrdoMapping};

use crate::drive::Drive;
use crate::store::{ParamId, Store};

/// One SRDO's normal-data parameters and their byte widths, in payload order.
#[derive(Debug, Clone)]
struct Fields(Vec<(ParamId, usize)>);

impl Fields {
    /// The normal entries of `srdo`, if all are byte-aligned parameters of the store.
    fn of(srdo: &SrdoMapping, device: &Device, store: &Store) -> Option<Self> {
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
    /// The valid-by-default SRDOs of the drive's description on `node`.
    pub fn new(store: &Store, node: NodeId) -> Self {
        let device = store.device();
        let mut srdos = Self::default();
        for srdo in device.srdos.iter().filter(|s| s.enabled) {
            if !srdos.add(srdo, device, store, node) {
                srdos.skipped.push(srdo.number);
            }
        }
        srdos
    }

    /// Adds one SRDO; false if the simulator cannot carry it.
    fn add(&mut self, srdo: &SrdoMapping, device: &Device, store: &Store, node: NodeId) -> bool {
        let (Some(fields), Some(objects)) =
            (Fields::of(srdo, device, store), srdo.mapped_objects(device))
        else {
            return false;
        };
        let [normal, inverted] = srdo.cob_ids.map(|c| c.resolve(Some(node.0)));
        let (Some(normal), Some(inverted)) = (normal, inverted) else {
            return false;
        };
        let Ok(ids) = drivebus::canopen::srdo::SrdoCobIds::from_objects(normal, inverted) else {
            return false;
        };
        let Ok(timing) =
            drivebus::canopen::srdo::SrdoTiming::from_millis(srdo.sct_ms, srdo.srvt_ms)
        else {
            return false;
        };
        let bits = data_bits(&objects);
        match srdo.direction {
            PdoDirection::Tx => match SrdoProducer::new(ids, timing.sct(), bits) {
                Ok(producer) => self.produced.push(Produced { producer, fields }),
                Err(_) => return false,
            },
            PdoDirection::Rx => match SrdoConsumer::new(ids, timing, bits) {
                Ok(consumer) => self.consumed.push(Consumed {
                    number: srdo.number,
                    consumer,
                    fields,
                }),
                Err(_) => return false,
            },
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

    /// Valid SRDOs the simulator cannot carry (bit-sized entries or unusable COB-IDs or times).
    pub fn skipped(&self) -> &[u8] {
        &self.skipped
    }
}
