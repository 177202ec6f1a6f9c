//! A network file checked against its descriptions before anything is sent: each node's
//! description loaded, its PDOs checked (`network_file::check_pdos`: the drive has the PDO and
//! can map every parameter), each boot parameter found, writable over CANopen and its value
//! parsed. Every refusal names the file and the line.

use std::path::{Path, PathBuf};

use drivebus::canopen::network::boot::{ExpectedIdentity, NodeBoot, PdoSetup};
use drivebus::canopen::NodeId;
use drivegen::ir::{Device, Parameter};
use drivegen::network_file::{self, NetworkFileError, NodeEntry};

use crate::error::CliError;

/// One node to boot, with its description and its boot writes.
pub struct Planned {
    /// The node as the file gives it.
    pub entry: NodeEntry,
    /// Its description.
    pub device: Device,
    /// The PDOs to configure, checked.
    pub pdos: Vec<PdoSetup>,
    /// The raw values to write: the parameter's name, its encoded value and its line.
    pub writes: Vec<(String, Vec<u8>, u32)>,
}

impl Planned {
    /// The boot procedure's part: probe, identity, heartbeat, PDOs (the parameters and the
    /// start are written through the interpreter afterwards).
    pub fn procedure(&self) -> NodeBoot {
        let identity = self.entry.identity;
        NodeBoot {
            node: NodeId(self.entry.id),
            identity: ExpectedIdentity {
                vendor_id: identity.vendor_id,
                product_code: identity.product_code,
                revision: identity.revision,
            },
            heartbeat: self
                .entry
                .heartbeat_ms
                .map(|ms| std::time::Duration::from_millis(u64::from(ms))),
            pdos: self.pdos.clone(),
            writes: Vec::new(),
            start: false,
        }
    }

    /// The parameter `name` of the node's description (checked when planned).
    pub fn parameter(&self, name: &str) -> Option<&Parameter> {
        self.device.parameter(name)
    }
}

/// Reads and checks `file`.
pub fn plan(file: &Path) -> Result<Vec<Planned>, CliError> {
    let shown = file.display().to_string();
    let refuse = |line: Option<u32>, reason: String| CliError::ConfigFile {
        file: shown.clone(),
        line,
        reason,
    };
    let text = std::fs::read_to_string(file).map_err(|e| refuse(None, e.to_string()))?;
    let parsed = network_file::parse(&text).map_err(|e| refuse(e.line, reason(&e)))?;
    let folder = file.parent().unwrap_or(Path::new("."));
    parsed
        .nodes
        .into_iter()
        .map(|entry| planned(folder, entry).map_err(|(line, why)| refuse(Some(line), why)))
        .collect()
}

fn planned(folder: &Path, entry: NodeEntry) -> Result<Planned, (u32, String)> {
    let path: PathBuf = folder.join(&entry.description);
    let checked = drivegen::check(&path);
    let Some(device) = checked.device else {
        return Err((
            entry.line,
            format!(
                "node {}: description {} cannot be used:\n{}",
                entry.id,
                path.display(),
                checked.render()
            ),
        ));
    };
    let pdos = network_file::check_pdos(&entry, &device).map_err(|e| {
        let line = e.line.unwrap_or(entry.line);
        (line, format!("node {}: {}", entry.id, reason(&e)))
    })?;
    let mut writes = Vec::new();
    for boot in &entry.parameters {
        let at = |why: String| {
            (
                boot.line,
                format!("node {}: {}: {why}", entry.id, boot.name),
            )
        };
        let parameter = device
            .parameter(&boot.name)
            .ok_or_else(|| at(format!("no such parameter in {}", device.device.name)))?;
        if !parameter.canopen.iter().any(|a| a.access.write) {
            return Err(at("not writable over CANopen".to_owned()));
        }
        let bytes = drivebus::interpret::parse(&device, parameter, &boot.value)
            .map_err(|cause| at(cause.to_string()))?;
        writes.push((boot.name.clone(), bytes, boot.line));
    }
    Ok(Planned {
        entry,
        device,
        pdos,
        writes,
    })
}

/// What is wrong, without the `line N: ` the refusal gives apart.
fn reason(error: &NetworkFileError) -> String {
    let shown = error.to_string();
    match error.line {
        Some(line) => shown
            .trim_start_matches(&format!("line {line}: "))
            .to_owned(),
        None => shown,
    }
}
