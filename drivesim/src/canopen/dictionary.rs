//! The drive's parameters as a CANopen object dictionary, enforcing access, length and range.

use std::collections::{BTreeMap, BTreeSet};

use drivebus::canopen::sdo::server::ObjectDictionary;
use drivebus::canopen::sdo::AbortCode;
use drivegen::ir::{Access, Device, ObjectAddress, Parameter};

use crate::refusal::Refusal;
use crate::store::ParamId;
use crate::Simulator;

/// The objects of a device, served from a running [`Simulator`].
#[derive(Debug, Clone)]
pub struct Dictionary {
    sim: Simulator,
    objects: BTreeMap<(u16, u8), (ParamId, Access)>,
    indices: BTreeSet<u16>,
}

impl Dictionary {
    /// The CANopen objects of `device` in `variant` (`None`: the default configuration).
    pub fn new(sim: Simulator, device: &Device, variant: Option<&str>) -> Self {
        Self::of(sim, device, variant, |p| &p.canopen)
    }

    /// The objects of `device` in `variant` at the object addresses `addresses` picks from each
    /// parameter (CANopen, or the Kinco RS-232 protocol, which addresses the same way).
    pub fn of(
        sim: Simulator,
        device: &Device,
        variant: Option<&str>,
        addresses: fn(&Parameter) -> &[ObjectAddress],
    ) -> Self {
        let mut objects = BTreeMap::new();
        for (id, parameter) in device.parameters.iter().enumerate() {
            if !crate::variant_selection::exists_in(parameter, variant) {
                continue;
            }
            for address in addresses(parameter)
                .iter()
                .filter(|a| a.variant.is_none() || a.variant.as_deref() == variant)
            {
                objects.insert((address.index, address.subindex), (id, address.access));
            }
        }
        let indices = objects.keys().map(|(index, _)| *index).collect();
        Self {
            sim,
            objects,
            indices,
        }
    }

    fn object(&self, index: u16, subindex: u8) -> Result<(ParamId, Access), Refusal> {
        match self.objects.get(&(index, subindex)) {
            Some(object) => Ok(*object),
            None if self.indices.contains(&index) => Err(Refusal::NoSuchSubindex),
            None => Err(Refusal::NoSuchAddress),
        }
    }

    /// Highest subindex of a record or array whose subindex 0 is not described.
    fn highest_subindex(&self, index: u16) -> u8 {
        self.objects
            .range((index, 0)..=(index, u8::MAX))
            .map(|((_, sub), _)| *sub)
            .max()
            .unwrap_or(0)
    }
}

impl ObjectDictionary for Dictionary {
    fn read(&mut self, index: u16, subindex: u8) -> Result<Vec<u8>, AbortCode> {
        match self.object(index, subindex) {
            Ok((_, access)) if !access.read => Err(Refusal::WriteOnly.sdo_abort()),
            Ok((id, _)) => Ok(self.sim.with(|drive| drive.store().bytes(id).to_vec())),
            Err(Refusal::NoSuchSubindex) if subindex == 0 => Ok(vec![self.highest_subindex(index)]),
            Err(refusal) => Err(refusal.sdo_abort()),
        }
    }

    fn check_writable(&mut self, index: u16, subindex: u8) -> Result<(), AbortCode> {
        match self.object(index, subindex).map_err(Refusal::sdo_abort)? {
            (_, access) if !access.write => Err(Refusal::ReadOnly.sdo_abort()),
            _ => Ok(()),
        }
    }

    fn write(&mut self, index: u16, subindex: u8, data: &[u8]) -> Result<(), AbortCode> {
        self.check_writable(index, subindex)?;
        let (id, _) = self.object(index, subindex).map_err(Refusal::sdo_abort)?;
        self.sim
            .with(|drive| drive.write(id, data))
            .map_err(Refusal::sdo_abort)
    }
}
