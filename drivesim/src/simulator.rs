//! [`Simulator`]: a shared handle on one simulated drive, and the servers that expose it.

use std::fmt;
use std::net::ToSocketAddrs;
use std::path::Path;
use std::sync::{Arc, Mutex};
use std::time::Instant;

use drivebus::modbus::UnitId;
use drivebus::rs232::{LoopMode, StationId};
use drivegen::ir::Device;

use crate::drive::Drive;
use crate::modbus::tcp::TcpServer;
use crate::modbus::ModbusServer;
use crate::rs232::Rs232Server;

/// Why a simulator could not be built or configured.
#[derive(Debug)]
pub enum SimError {
    /// The description has errors (rendered diagnostics).
    Invalid(String),
    /// No parameter of this name.
    UnknownParameter(String),
    /// An I/O failure starting a server.
    Io(std::io::Error),
}

impl fmt::Display for SimError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SimError::Invalid(diagnostics) => write!(f, "invalid description:\n{diagnostics}"),
            SimError::UnknownParameter(name) => write!(f, "no parameter named `{name}`"),
            SimError::Io(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for SimError {}

impl From<std::io::Error> for SimError {
    fn from(e: std::io::Error) -> Self {
        SimError::Io(e)
    }
}

#[derive(Debug)]
struct Inner {
    drive: Drive,
    last: Instant,
}

/// A simulated drive shared by its servers; cloning gives another handle on the same drive.
///
/// Time passes in real time: before each request the drive advances by the time since the
/// previous one, so ramps run while a client polls.
#[derive(Debug, Clone)]
pub struct Simulator {
    inner: Arc<Mutex<Inner>>,
    variant: Option<String>,
}

impl Simulator {
    /// A drive built from the description at `path` (a file, or a folder with `device.toml`).
    pub fn load(path: impl AsRef<Path>) -> Result<Self, SimError> {
        let checked = drivegen::check(path.as_ref());
        match checked.device {
            Some(device) => Ok(Self::new(device)),
            None => Err(SimError::Invalid(checked.render())),
        }
    }

    /// A drive built from a device model, in its default variant. The communication and mapping
    /// objects of its declared PDOs are served too, as the exported EDS lists them.
    pub fn new(device: Device) -> Self {
        let device = with_pdo_objects(device);
        let variant = device.variants.first().map(|v| v.name.clone());
        let identity = crate::identity::covered_identity(&device);
        let sim = Self {
            inner: Arc::new(Mutex::new(Inner {
                drive: Drive::new(device),
                last: Instant::now(),
            })),
            variant,
        };
        if let Some((name, value)) = identity {
            // The parameter is described and the value fits its type (identity_names_a_parameter).
            let _ = sim.preset(&name, value);
        }
        sim
    }

    /// Runs `f` on the drive after advancing it to the present time.
    pub fn with<R>(&self, f: impl FnOnce(&mut Drive) -> R) -> R {
        let mut inner = self.inner.lock().unwrap_or_else(|e| e.into_inner());
        let now = Instant::now();
        let dt = now - inner.last;
        inner.last = now;
        inner.drive.tick(dt);
        f(&mut inner.drive)
    }

    /// Presets parameter `name` to `raw` as the drive's own configuration or measurement.
    pub fn preset(&self, name: &str, raw: i128) -> Result<&Self, SimError> {
        self.with(|drive| {
            let id = drive
                .store()
                .id(name)
                .ok_or_else(|| SimError::UnknownParameter(name.to_string()))?;
            drive.preset(id, raw);
            Ok(self)
        })
    }

    /// The variant served (`None` when the description has no variants).
    pub fn variant(&self) -> Option<&str> {
        self.variant.as_deref()
    }

    /// The Modbus request handler for this drive, in the variant its selecting parameter names
    /// (`selected_by`), else the one served by default.
    pub fn modbus_server(&self) -> ModbusServer {
        self.with(|drive| {
            let selected = crate::variant_selection::selected_variant(drive.store());
            ModbusServer::new(
                drive.store().device(),
                selected.as_deref().or(self.variant()),
            )
        })
    }

    /// The Kinco RS-232 telegram handler for this drive at `station`.
    pub fn rs232_server(&self, station: StationId, mode: LoopMode) -> Rs232Server {
        Rs232Server::new(self, station, mode)
    }

    /// Serves Modbus TCP on `addr` (use `127.0.0.1:0` for a free port) for `unit`.
    pub fn serve_modbus_tcp(
        &self,
        addr: impl ToSocketAddrs,
        unit: UnitId,
    ) -> Result<TcpServer, SimError> {
        Ok(TcpServer::start(self.clone(), addr, unit)?)
    }
}

/// `device` plus the PDO communication and mapping objects its `[[pdo]]` tables imply and it does
/// not describe itself (`drivegen::eds::pdo_objects`, the same objects the EDS export writes).
fn with_pdo_objects(mut device: Device) -> Device {
    let derived = drivegen::eds::pdo_objects(&device);
    device.records.extend(derived.records);
    device.parameters.extend(derived.parameters);
    device
}
