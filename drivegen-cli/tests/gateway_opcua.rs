//! `drivegen gateway`'s OPC UA endpoint (feature `opcua`) with python asyncua as the independent
//! client, the simulated drives of two families (Lafert and Lenze, on Modbus TCP) behind it:
//! browse, values with their EngineeringUnits and EURange, enums, a write that lands, writes
//! refused with their status codes (the locked Lenze's own refusal among them), a subscription, users with and without the write right on a
//! Basic256Sha256 Sign&Encrypt endpoint (the client's certificate made here and trusted the way
//! an operator would: moved from `pki/rejected` to `pki/trusted`), a drive that stops answering.
//! Without the feature, a file with `[opcua]` is refused with the feature's name.
// Without the feature only the refusal runs, and most helpers are unused.
#![cfg_attr(not(feature = "opcua"), allow(dead_code, unused_imports))]

// Each test binary uses part of the helpers.
#[allow(dead_code)]
mod support;

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

use peer_support::{mosquitto::free_port, Process};
use support::BIN;

/// Everything here answers within seconds; a spawned process gets this much to start.
const WAIT: Duration = Duration::from_secs(30);

fn description(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../descriptions")
        .join(name)
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("drivegen-opcua-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A gateway file serving OPC UA alone on `port`: two drives, an operator who may write, a
/// viewer who may not, anonymous readers.
fn config(dir: &Path, port: u16, lafert: &str, lenze: &str) -> PathBuf {
    let file = dir.join("gateway.toml");
    std::fs::write(
        &file,
        format!(
            r#"format = 1

[opcua]
port = {port}
pki_dir = "pki"
anonymous = true
sampling_interval_ms = 100

[[opcua.user]]
name = "operator"
password_env = "OPERATOR_PASSWORD"
right = "write"

[[opcua.user]]
name = "viewer"
password_env = "VIEWER_PASSWORD"
right = "read"

[[drive]]
name = "lafert"
description = "{}"
bus = {{ modbus_tcp = "{lafert}", timeout_ms = 300 }}
interval_ms = 100
parameters = ["bus_dc_link", "speed_ramp_up", "operation_mode"]
writable = ["speed_ramp_up", "operation_mode"]

[[drive]]
name = "lenze"
description = "{}"
bus = {{ modbus_tcp = "{lenze}", timeout_ms = 300 }}
interval_ms = 100
parameters = ["acceleration_time", "current_limit"]
writable = ["acceleration_time"]
"#,
            description("lafert-smartris").display(),
            description("lenze-smd").display(),
        ),
    )
    .unwrap();
    file
}

/// The python client (tests/peers/opcua_client.py) in `mode`; its stdout, once it succeeded.
fn client(args: &[&str]) -> String {
    let script = peer_support::peers_dir().join("opcua_client.py");
    let output = Command::new(peer_support::python())
        .arg(script)
        .args(args)
        .env("OPERATOR_PASSWORD", "op-secret")
        .env("VIEWER_PASSWORD", "view-secret")
        .output()
        .unwrap_or_else(|e| panic!("python: {e}; {}", peer_support::SETUP_HINT));
    assert!(
        output.status.success(),
        "opcua_client.py {args:?}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8_lossy(&output.stdout).trim().to_owned()
}

fn json(text: &str) -> serde_json::Value {
    serde_json::from_str(text).unwrap_or_else(|e| panic!("{text}: {e}"))
}

/// `drivegen gateway FILE` with the users' passwords, its log in `dir/gateway.log`, once it
/// serves OPC UA.
fn start_gateway(dir: &Path, file: &Path) -> Process {
    let log = std::fs::File::create(dir.join("gateway.log")).unwrap();
    let gateway = Process::new(
        Command::new(BIN)
            .arg("gateway")
            .arg(file)
            .env("OPERATOR_PASSWORD", "op-secret")
            .env("VIEWER_PASSWORD", "view-secret")
            .stderr(log)
            .spawn()
            .unwrap(),
    );
    serving(&dir.join("gateway.log"));
    gateway
}

/// Waits until the gateway's log says it serves OPC UA (its port is bound from the start, but
/// the first start makes the server's key first).
fn serving(log: &Path) {
    logged(log, "OPC UA serving");
}

/// Waits until the gateway's log has `line` (four times [`WAIT`]: a debug build takes a while
/// to make the server's RSA key).
fn logged(log: &Path, line: &str) {
    let started = Instant::now();
    loop {
        let text = std::fs::read_to_string(log).unwrap_or_default();
        if text.contains(line) {
            return;
        }
        assert!(started.elapsed() < WAIT * 4, "no `{line}`:\n{text}");
        std::thread::sleep(Duration::from_millis(50));
    }
}

#[cfg(feature = "opcua")]
#[test]
fn an_independent_client_browses_reads_writes_and_subscribes() {
    let dir = scratch("live");
    let key_dir = dir.join("client");
    std::fs::create_dir_all(&key_dir).unwrap();
    client(&["cert", key_dir.to_str().unwrap()]);
    let (lafert_sim, lafert) = support::modbus_sim(
        &description("lafert-smartris"),
        &["--set", "bus_dc_link=4950", "--set", "operation_mode=2"],
    );
    let _lafert_sim = Process::new(lafert_sim);
    let (lenze_sim, lenze) = support::modbus_sim(&description("lenze-smd"), &[]);
    let mut lenze_sim = Process::new(lenze_sim);
    let port = free_port();
    let file = config(&dir, port, &lafert, &lenze);
    let mut gateway = start_gateway(&dir, &file);
    let url = format!("opc.tcp://127.0.0.1:{port}/");

    // An unknown client certificate is refused and kept in pki/rejected; the operator trusts it
    // by moving it to pki/trusted (the server's own certificate was made in pki/own).
    assert!(dir.join("pki/own/cert.der").exists());
    let refused = json(&client(&["untrusted", &url, key_dir.to_str().unwrap()]));
    assert_ne!(refused["secure"], "connected", "{refused}");
    let rejected: Vec<_> = std::fs::read_dir(dir.join("pki/rejected"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    assert_eq!(rejected.len(), 1, "{rejected:?}");
    let trusted = dir
        .join("pki/trusted")
        .join(rejected[0].file_name().unwrap());
    std::fs::rename(&rejected[0], trusted).unwrap();

    let seen = json(&client(&["check", &url, key_dir.to_str().unwrap()]));
    // A folder per drive, a variable per exposed parameter.
    assert_eq!(
        seen["folders"],
        serde_json::json!(["lafert", "lenze"]),
        "{seen}"
    );
    assert_eq!(
        seen["lafert_variables"],
        serde_json::json!(["bus_dc_link", "operation_mode", "speed_ramp_up"])
    );
    // A scaled value: a Double in volts, with its UNECE unit, its poll time, read only.
    let dc = &seen["lafert.bus_dc_link"];
    assert_eq!(dc["value"], 49.5, "{dc}");
    assert_eq!(dc["type"], "Double");
    assert_eq!(dc["status"], "Good");
    assert_eq!(dc["has_source_time"], true);
    assert_eq!(dc["unit"]["name"], "V");
    assert_eq!(dc["unit"]["id"], 5655636, "VLT");
    assert_eq!(
        dc["unit"]["ns"],
        "http://www.opcfoundation.org/UA/units/un/cefact"
    );
    assert_eq!((&dc["access"], &dc["user_access"]), (&1.into(), &1.into()));
    // An integer with its range; writable, but not by an anonymous reader.
    let ramp = &seen["lafert.speed_ramp_up"];
    assert_eq!(ramp["type"], "UInt16", "{ramp}");
    assert_eq!(ramp["range"], serde_json::json!([0.0, 32000.0]));
    assert_eq!(ramp["unit"]["id"], 4403766, "C26, millisecond");
    assert_eq!(
        (&ramp["access"], &ramp["user_access"]),
        (&3.into(), &1.into())
    );
    // An enum: its raw value and its names.
    let mode = &seen["lafert.operation_mode"];
    assert_eq!(mode["value"], 2, "{mode}");
    assert_eq!(mode["enum"]["velocity"], 2, "{mode}");
    assert_eq!(mode["enum"]["torque"], 1, "{mode}");
    // The second family: a scaled time in seconds with its range in seconds.
    let accel = &seen["lenze.acceleration_time"];
    assert_eq!(accel["type"], "Double", "{accel}");
    assert_eq!(accel["value"], 5.0, "{accel}");
    assert_eq!(accel["range"], serde_json::json!([0.0, 999.0]));
    assert_eq!(accel["unit"]["id"], 5457219, "SEC");
    assert_eq!(
        seen["lenze.current_limit"]["access"], 1,
        "not in `writable`"
    );

    assert_eq!(seen["anonymous_write"], "BadUserAccessDenied");
    let writes = &seen["operator_writes"];
    assert_eq!(writes["ramp_1500"], "Good", "{writes}");
    assert_eq!(writes["ramp_out_of_range"], "BadOutOfRange", "{writes}");
    assert_eq!(writes["ramp_wrong_type"], "BadTypeMismatch", "{writes}");
    assert_eq!(writes["mode_torque"], "Good", "{writes}");
    assert_eq!(writes["mode_unknown"], "BadOutOfRange", "{writes}");
    // The Lenze is locked until a password unlocks it (its description's lock rules), which
    // the gateway does not do: the drive refuses with exception 01, nothing is written.
    assert_eq!(writes["lenze_accel"], "BadNotWritable", "{writes}");
    assert_eq!(
        writes["lenze_accel_out_of_range"], "BadOutOfRange",
        "{writes}"
    );
    assert_eq!(writes["lenze_current_limit"], "BadNotWritable", "{writes}");
    // The write landed on the simulated drive (read back through its polls); the refused did not.
    assert_eq!(seen["ramp_read_back"], 1500, "{seen}");
    assert_eq!(seen["accel_after"], 5.0, "{seen}");
    let changes = seen["subscription_values"].as_array().unwrap();
    assert!(changes.contains(&1500.into()), "{changes:?}");
    assert_eq!(seen["viewer_read"], 1500);
    assert_eq!(seen["viewer_write"], "BadUserAccessDenied");
    assert_ne!(seen["wrong_password"], "connected");

    // A drive that stops answering: its variables go Bad, the other drive's stay Good.
    lenze_sim.child_mut().kill().unwrap();
    let started = Instant::now();
    loop {
        let read = json(&client(&["status", &url, "lenze.acceleration_time"]));
        if read["status"] == "BadCommunicationError" {
            break;
        }
        assert_eq!(read["status"], "Good", "{read}");
        assert!(started.elapsed() < WAIT, "still {read}");
        std::thread::sleep(Duration::from_millis(200));
    }
    let other = json(&client(&["status", &url, "lafert.bus_dc_link"]));
    assert_eq!(other["status"], "Good", "{other}");

    // SIGTERM: a clean stop. The refused writes were logged with who asked.
    let exit = support::terminate(gateway.child_mut());
    assert!(exit.success(), "{exit}");
    let log = std::fs::read_to_string(dir.join("gateway.log")).unwrap();
    assert!(log.contains("the user has no write right"), "{log}");
    assert!(log.contains("viewer"), "{log}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[cfg(feature = "opcua")]
#[test]
fn mqtt_and_opcua_serve_the_same_polls_from_one_process() {
    let dir = scratch("both");
    let broker_port = free_port();
    let _broker = peer_support::mosquitto::start(&dir, broker_port, "allow_anonymous true\n");
    let (lafert_sim, lafert) = support::modbus_sim(&description("lafert-smartris"), &[]);
    let _lafert_sim = Process::new(lafert_sim);
    let port = free_port();
    let file = config(&dir, port, &lafert, "127.0.0.1:1");
    let text = std::fs::read_to_string(&file).unwrap();
    let both = text.replacen(
        "[opcua]",
        &format!("[mqtt]\nport = {broker_port}\n\n[opcua]"),
        1,
    );
    std::fs::write(&file, both).unwrap();
    let _gateway = start_gateway(&dir, &file);
    // Set messages are not retained: the gateway must have subscribed first.
    logged(
        &dir.join("gateway.log"),
        "connected to the broker drive=lafert",
    );
    let url = format!("opc.tcp://127.0.0.1:{port}/");
    // A write from an MQTT client is seen by OPC UA clients at the next poll.
    let published = Command::new("mosquitto_pub")
        .args(["-h", "127.0.0.1", "-p", &broker_port.to_string()])
        .args([
            "-t",
            "drivegen/lafert/speed_ramp_up/set",
            "-m",
            r#"{"value": 1800}"#,
        ])
        .status()
        .unwrap();
    assert!(published.success());
    let started = Instant::now();
    loop {
        let read = json(&client(&["status", &url, "lafert.speed_ramp_up"]));
        if read["value"] == 1800 {
            assert_eq!(read["status"], "Good", "{read}");
            break;
        }
        assert!(started.elapsed() < WAIT, "still {read}");
        std::thread::sleep(Duration::from_millis(200));
    }
    // And MQTT keeps publishing the drive's values beside (retained).
    let retained = Command::new("mosquitto_sub")
        .args(["-h", "127.0.0.1", "-p", &broker_port.to_string()])
        .args(["-t", "drivegen/lafert/speed_ramp_up", "-C", "1", "-W", "10"])
        .output()
        .unwrap();
    let value = json(&String::from_utf8_lossy(&retained.stdout));
    assert_eq!(value["raw"], 1800, "{value}");
    // The dead Lenze bus: Bad on OPC UA, the Lafert served all the same.
    let lenze = json(&client(&["status", &url, "lenze.acceleration_time"]));
    assert_ne!(lenze["status"], "Good", "{lenze}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `drivegen gateway FILE` for a file it must refuse (the operator's password unset): its
/// stderr.
fn refusal(file: &Path) -> String {
    support::refused(
        Command::new(BIN)
            .arg("gateway")
            .arg(file)
            .env_remove("OPERATOR_PASSWORD")
            .env("VIEWER_PASSWORD", "view-secret"),
    )
}

#[cfg(feature = "opcua")]
#[test]
fn a_missing_password_is_refused_before_anything_opens() {
    let dir = scratch("nopass");
    let port = free_port();
    let file = config(&dir, port, "127.0.0.1:1", "127.0.0.1:1");
    let message = refusal(&file);
    assert!(message.contains("OPERATOR_PASSWORD"), "{message}");
    assert!(!dir.join("pki").exists(), "nothing was made");
    let _ = std::fs::remove_dir_all(&dir);
}

#[cfg(not(feature = "opcua"))]
#[test]
fn without_the_feature_an_opcua_table_is_refused_with_its_name() {
    let dir = scratch("nofeature");
    let file = config(&dir, free_port(), "127.0.0.1:1", "127.0.0.1:1");
    let message = refusal(&file);
    assert!(message.contains("gateway.toml:3"), "{message}");
    assert!(message.contains("`opcua` feature"), "{message}");
    let _ = std::fs::remove_dir_all(&dir);
}
