//! The Modbus scan: every unit id of a range is asked for the identity register of each
//! candidate description (the `[identity]` parameter, e.g. the Lafert firmware release, the smd
//! configuration register #50). A unit that stays silent at the first probe (or for which a
//! gateway answers exception 0x0A / 0x0B) is absent and costs at most one timeout; a unit that answers, even with an exception, is listed with what each probe
//! found. Over TCP several connections probe units at once; a serial line is one bus, probed
//! unit after unit.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::Duration;

use drivebus::modbus::client::{ModbusTcpClient, SerialConfig, SerialRtuClient, TcpConfig};
use drivebus::modbus::retry::RetryPolicy;
use drivebus::modbus::{ExceptionCode, ModbusLimits, RegisterBus, UnitId};
use drivebus::BusError;
use drivegen::ir::{Device, IdentityCheck};

use super::{names, verdict, Answer};
use crate::codec;
use crate::connect::read_modbus;
use crate::error::CliError;
use drivebus::interpret::Variant;

/// One candidate description's identity register.
pub struct Probe<'a> {
    device: &'a Device,
    check: IdentityCheck<'a>,
    limits: ModbusLimits<'a>,
}

/// What one probe found at one unit.
enum Reading {
    /// The identity parameter's raw value (as shown) and whether the description covers it.
    Value {
        raw: serde_json::Value,
        covered: bool,
    },
    /// The unit answered with an exception, or an answer that is not one.
    Refused(String),
}

/// The probes of every description's identity parameters that have a readable Modbus address.
pub fn probes(devices: &[Device]) -> Result<Vec<Probe<'_>>, CliError> {
    let probes: Vec<Probe> = devices
        .iter()
        .flat_map(|device| {
            let limits = device.modbus_limits();
            device
                .identity_checks()
                .into_iter()
                .filter(|check| check.parameter.readable_over_modbus())
                .map(move |check| Probe {
                    device,
                    check,
                    limits,
                })
        })
        .collect();
    if probes.is_empty() {
        return Err(CliError::Usage(
            "no description has an [identity] parameter with a Modbus address to probe with".into(),
        ));
    }
    Ok(probes)
}

/// Probes `units` over Modbus TCP at `addr` with up to `connections` connections at once.
pub fn scan_tcp(
    addr: &str,
    units: &[u8],
    probes: &[Probe],
    timeout: Duration,
    connections: usize,
) -> Result<Vec<Answer>, CliError> {
    let config = TcpConfig {
        timeout,
        retry: RetryPolicy::NONE,
        ..TcpConfig::default()
    };
    let next = AtomicUsize::new(0);
    let found = Mutex::new(Vec::new());
    let target = format!("Modbus TCP {addr}");
    std::thread::scope(|scope| {
        let workers: Vec<_> = (0..connections.min(units.len()))
            .map(|_| {
                scope.spawn(|| -> Result<(), CliError> {
                    let mut bus = ModbusTcpClient::connect(addr, &config)
                        .map_err(|e| CliError::Io(format!("cannot open {target}: {e}")))?;
                    while let Some(&unit) = units.get(next.fetch_add(1, Ordering::Relaxed)) {
                        if let Some(answer) = probe_unit(&mut bus, unit, probes, &target) {
                            found.lock().unwrap_or_else(|e| e.into_inner()).push(answer);
                        }
                    }
                    Ok(())
                })
            })
            .collect();
        workers
            .into_iter()
            .try_for_each(|w| w.join().unwrap_or_else(|_| Err(worker_failed())))
    })?;
    let mut found = found.into_inner().unwrap_or_else(|e| e.into_inner());
    found.sort_by_key(|(unit, _)| *unit);
    Ok(found.into_iter().map(|(_, answer)| answer).collect())
}

fn worker_failed() -> CliError {
    CliError::Io("a probing connection failed".into())
}

/// Probes `units` over Modbus RTU on `path`, one unit after the other.
pub fn scan_rtu(
    path: &str,
    line: &SerialConfig,
    units: &[u8],
    probes: &[Probe],
) -> Result<Vec<Answer>, CliError> {
    let config = SerialConfig {
        retry: RetryPolicy::NONE,
        ..line.clone()
    };
    let target = format!("Modbus RTU {path}");
    let mut bus = SerialRtuClient::open(path, &config)
        .map_err(|e| CliError::Io(format!("cannot open {target}: {e}")))?;
    Ok(units
        .iter()
        .filter_map(|&unit| probe_unit(&mut bus, unit, probes, &target))
        .map(|(_, answer)| answer)
        .collect())
}

/// Every probe at `unit`, or `None` when the unit is silent at the first.
fn probe_unit(
    bus: &mut dyn RegisterBus,
    unit: u8,
    probes: &[Probe],
    target: &str,
) -> Option<(u8, Answer)> {
    let target = format!("{target} unit {unit}");
    let mut readings = Vec::new();
    for probe in probes {
        let parameters = [probe.check.parameter];
        // The drive's variant is not known yet: identity parameters have one address in all.
        let undetected = Variant::Unknown {
            selector: probe
                .device
                .variant_selection()
                .map_or_else(String::new, |(p, _)| p.name.clone()),
            found: None,
        };
        let read = read_modbus(
            bus,
            UnitId(unit),
            probe.limits,
            &target,
            &undetected,
            &parameters,
        );
        let reading = match read {
            Ok(values) => {
                let bytes = values.into_iter().next().unwrap_or_default();
                let shown = drivebus::interpret::show(probe.device, probe.check.parameter, &bytes);
                let raw = codec::raw_json(&shown.raw);
                let covered = raw
                    .as_i64()
                    .is_some_and(|v| probe.check.covered.contains(v.into()));
                Reading::Value { raw, covered }
            }
            Err(CliError::Bus { cause, .. }) if readings.is_empty() && absent(&cause) => {
                return None
            }
            Err(CliError::Bus { cause, .. }) => Reading::Refused(cause.to_string()),
            Err(other) => Reading::Refused(other.to_string()),
        };
        readings.push(reading);
    }
    Some((unit, answer(unit, probes, &readings)))
}

/// Whether `cause` says nobody is at the unit: silence, or a gateway's exception 0x0A (no path
/// to the target) or 0x0B (the target did not respond), as Modbus TCP gateways answer for an
/// empty unit id.
fn absent(cause: &BusError) -> bool {
    matches!(
        cause,
        BusError::Timeout
            | BusError::ModbusException {
                code: ExceptionCode::GatewayPathUnavailable
                    | ExceptionCode::GatewayTargetFailedToRespond,
                ..
            }
    )
}

fn answer(unit: u8, probes: &[Probe], readings: &[Reading]) -> Answer {
    let matches: Vec<&Device> = probes
        .iter()
        .zip(readings)
        .filter(|(_, r)| matches!(r, Reading::Value { covered: true, .. }))
        .map(|(p, _)| p.device)
        .collect();
    let found: Vec<String> = probes
        .iter()
        .zip(readings)
        .map(|(p, r)| shown(p, r))
        .collect();
    let line = format!("unit {unit:3}: {}: {}", found.join("; "), verdict(&matches));
    let identity: Vec<serde_json::Value> = probes
        .iter()
        .zip(readings)
        .map(|(p, r)| json(p, r))
        .collect();
    let json = serde_json::json!({
        "unit": unit,
        "identity": identity,
        "matches": names(&matches),
    });
    Answer { line, json }
}

/// `Lafert Smartris fw_release = 242`, or `... fw_release: <why not>`.
fn shown(probe: &Probe, reading: &Reading) -> String {
    let name = format!(
        "{} {}",
        probe.device.device.name, probe.check.parameter.name
    );
    match reading {
        Reading::Value { raw, .. } => format!("{name} = {raw}"),
        Reading::Refused(why) => format!("{name}: {why}"),
    }
}

fn json(probe: &Probe, reading: &Reading) -> serde_json::Value {
    let mut object = serde_json::json!({
        "description": probe.device.device.name,
        "parameter": probe.check.parameter.name,
        "expected": probe.check.covered,
    });
    match reading {
        Reading::Value { raw, covered } => {
            object["raw"] = raw.clone();
            object["covered"] = (*covered).into();
        }
        Reading::Refused(why) => object["error"] = why.clone().into(),
    }
    object
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn silence_and_a_gateways_no_target_exceptions_mean_nobody_is_there() {
        let gateway = |code| BusError::ModbusException {
            function: 0x03,
            code,
        };
        assert!(absent(&BusError::Timeout));
        assert!(absent(&gateway(ExceptionCode::GatewayPathUnavailable)));
        assert!(absent(&gateway(
            ExceptionCode::GatewayTargetFailedToRespond
        )));
        assert!(
            !absent(&gateway(ExceptionCode::IllegalDataAddress)),
            "a drive refusing the address is there"
        );
    }
}
