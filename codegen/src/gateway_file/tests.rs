use super::*;

const GOOD: &str = r#"format = 1

[mqtt]
port = 18830
username = "gateway"
password_env = "GATEWAY_PASSWORD"

[[drive]]
name = "left-wheel"
description = "lafert.toml"
bus = { modbus_tcp = "127.0.0.1:5020", unit = 3, timeout_ms = 200 }
interval_ms = 100
parameters = ["bus_dc_link", "speed_setpoint"]
writable = ["speed_setpoint"]

[[drive]]
name = "kinco"
description = "/abs/kinco"
bus = { kinco_rs232 = "/dev/ttyUSB0", rs232_loop = true, node_id = 2 }
parameters = ["actual_velocity"]
"#;

#[test]
fn a_whole_file_reads_with_defaults_and_lines() {
    let file = parse(GOOD).unwrap();
    let mqtt = file.mqtt.expect("[mqtt]");
    assert_eq!(mqtt.host, "127.0.0.1");
    assert_eq!(mqtt.port, 18830);
    assert_eq!(mqtt.topic_prefix, "drivegen");
    assert_eq!(mqtt.password_env.as_deref(), Some("GATEWAY_PASSWORD"));
    assert_eq!(file.opcua, None);
    assert!(!file.read_only);
    let [left, kinco] = file.drives.as_slice() else {
        panic!("two drives expected: {:?}", file.drives)
    };
    assert_eq!(left.name, "left-wheel");
    assert_eq!(left.line, 8);
    assert_eq!(left.interval_ms, 100);
    let options: Vec<_> = left
        .bus
        .iter()
        .map(|o| (o.name.as_str(), o.value.as_deref(), o.line))
        .collect();
    assert_eq!(
        options,
        [
            ("modbus_tcp", Some("127.0.0.1:5020"), 11),
            ("unit", Some("3"), 11),
            ("timeout_ms", Some("200"), 11)
        ]
    );
    assert_eq!(left.writable[0].name, "speed_setpoint");
    assert_eq!(left.writable[0].line, 14);
    assert_eq!(kinco.interval_ms, 500);
    assert!(kinco.writable.is_empty());
    assert_eq!(kinco.bus[1].name, "rs232_loop");
    assert_eq!(kinco.bus[1].value, None);
}

fn refused(text: &str) -> GatewayFileError {
    parse(text).expect_err("refused")
}

#[test]
fn a_drive_name_twice_is_refused_at_its_second_entry() {
    let text = format!(
        "{GOOD}\n[[drive]]\nname = \"kinco\"\ndescription = \"x\"\nbus = {{ can = \"x\" }}\nparameters = [\"a\"]\n"
    );
    let error = refused(&text);
    assert_eq!(
        error.kind,
        GatewayFileErrorKind::DuplicateDrive("kinco".into())
    );
    assert_eq!(error.line, Some(22));
}

#[test]
fn a_name_that_is_not_one_topic_level_is_refused() {
    let text = GOOD.replace("left-wheel", "left/+");
    let error = refused(&text);
    assert_eq!(error.line, Some(9));
    assert!(error.to_string().contains("topic level"), "{error}");
}

#[test]
fn shapes_out_of_range_are_refused_with_their_line() {
    let cases = [
        (GOOD.replace("port = 18830", "port = 70000"), 4, "port"),
        (
            GOOD.replace("interval_ms = 100", "interval_ms = 0"),
            12,
            "interval_ms",
        ),
        (GOOD.replace("unit = 3", "unit = [3]"), 11, "unit"),
        (
            GOOD.replace("parameters = [\"actual_velocity\"]", "parameters = []"),
            16,
            "parameters",
        ),
    ];
    for (text, line, key) in cases {
        let error = refused(&text);
        assert_eq!(error.line, Some(line), "{key}: {error}");
        assert!(error.to_string().contains(key), "{key}: {error}");
    }
}

#[test]
fn unknown_keys_missing_format_and_no_drives_are_refused() {
    assert!(matches!(
        refused(&GOOD.replace("interval_ms", "intervall_ms")).kind,
        GatewayFileErrorKind::Syntax(_)
    ));
    assert_eq!(
        refused(&GOOD.replace("format = 1", "")).kind,
        GatewayFileErrorKind::MissingFormat
    );
    assert_eq!(refused("format = 1\n").kind, GatewayFileErrorKind::NoDrives);
    assert_eq!(
        refused(&GOOD.replace("format = 1", "format = 2")).kind,
        GatewayFileErrorKind::UnsupportedFormat(2)
    );
}

#[test]
fn tls_takes_a_ca_and_a_client_certificate_only_with_its_key() {
    let with_tls = GOOD.replace(
        "port = 18830\n",
        "port = 18830\nca_file = \"ca.pem\"\nclient_cert_file = \"gw.pem\"\nclient_key_file = \"gw.key\"\n",
    );
    let tls = parse(&with_tls).unwrap().mqtt.unwrap().tls.expect("tls");
    assert_eq!(tls.ca_file, "ca.pem");
    assert_eq!(tls.client, Some(("gw.pem".into(), "gw.key".into())));
    assert_eq!(parse(GOOD).unwrap().mqtt.unwrap().tls, None);
    let no_key = with_tls.replace("client_key_file = \"gw.key\"\n", "");
    let error = refused(&no_key);
    assert_eq!(error.line, Some(3));
    assert!(error.to_string().contains("together"), "{error}");
    let no_ca = with_tls.replace("ca_file = \"ca.pem\"\n", "");
    assert!(refused(&no_ca).to_string().contains("CA"));
}

#[test]
fn pdo_use_is_read_and_pdo_start_needs_it() {
    let file = parse(GOOD).unwrap();
    assert!(file.drives[0].pdo == PdoUse::Off && !file.drives[0].pdo_start);
    let with = |pdo: &str| {
        GOOD.replace(
            "writable = [\"speed_setpoint\"]\n",
            &format!("writable = [\"speed_setpoint\"]\n{pdo}\n"),
        )
    };
    let left = &parse(&with("pdo = true\npdo_start = true")).unwrap().drives[0];
    assert!(left.pdo == PdoUse::Sync && left.pdo_start);
    for (written, read) in [
        ("\"sync\"", PdoUse::Sync),
        ("\"event\"", PdoUse::Event),
        ("false", PdoUse::Off),
    ] {
        let file = parse(&with(&format!("pdo = {written}"))).unwrap();
        assert_eq!(file.drives[0].pdo, read, "{written}");
    }
    let error = refused(&with("pdo = \"often\""));
    assert_eq!(error.line, Some(15), "the line of the value");
    assert!(error.to_string().contains("\"event\""), "{error}");
    let error = refused(&with("pdo_start = true"));
    assert_eq!(error.line, Some(8));
    assert!(error.to_string().contains("pdo = true"), "{error}");
    // The event timer holds 16 bits of milliseconds.
    let slow = with("pdo = \"event\"").replace("interval_ms = 100", "interval_ms = 70000");
    assert!(refused(&slow).to_string().contains("65535"), "{slow}");
}

/// GOOD with an `[opcua]` table (lines 3-15) instead of `[mqtt]`.
fn with_opcua(table: &str) -> String {
    let drives = GOOD.split_once("\n[[drive]]").expect("drives").1;
    format!("format = 1\n\n{table}\n[[drive]]{drives}")
}

const OPCUA: &str = r#"[opcua]
port = 48400
pki_dir = "pki"
sampling_interval_ms = 50

[[opcua.user]]
name = "operator"
password_env = "OPERATOR_PASSWORD"
right = "write"

[[opcua.user]]
name = "viewer"
password_env = "VIEWER_PASSWORD"
right = "read"
"#;

#[test]
fn an_opcua_table_reads_with_its_users_and_alone_turns_mqtt_off() {
    let file = parse(&with_opcua(OPCUA)).unwrap();
    assert_eq!(file.mqtt, None);
    let opcua = file.opcua.expect("[opcua]");
    assert_eq!(opcua.host, "127.0.0.1");
    assert_eq!(opcua.port, 48400);
    assert_eq!(opcua.sampling_interval_ms, 50);
    assert_eq!(opcua.line, 3);
    assert!(!opcua.anonymous);
    let users: Vec<_> = opcua
        .users
        .iter()
        .map(|u| (u.name.as_str(), u.password_env.as_str(), u.right, u.line))
        .collect();
    assert_eq!(
        users,
        [
            ("operator", "OPERATOR_PASSWORD", OpcUaRight::Write, 9),
            ("viewer", "VIEWER_PASSWORD", OpcUaRight::Read, 14),
        ]
    );
    assert_eq!(file.drives.len(), 2);
    // Both tables: both endpoints.
    let both = GOOD.replacen("[mqtt]", &format!("{OPCUA}\n[mqtt]"), 1);
    let file = parse(&both).unwrap();
    assert!(file.mqtt.is_some() && file.opcua.is_some());
}

#[test]
fn opcua_defaults_and_refusals_carry_their_line() {
    let anonymous = parse(&with_opcua("[opcua]\nanonymous = true\n")).unwrap();
    let opcua = anonymous.opcua.unwrap();
    assert_eq!((opcua.port, opcua.pki_dir.as_str()), (4840, "pki"));
    assert_eq!(opcua.sampling_interval_ms, 100);
    let cases = [
        (
            with_opcua("[opcua]\nport = 18830\n"),
            3,
            "no client could log in",
        ),
        (with_opcua(&OPCUA.replace("48400", "0")), 4, "port"),
        (
            with_opcua(&OPCUA.replace("= 50", "= 0")),
            6,
            "sampling_interval_ms",
        ),
        (
            with_opcua(&OPCUA.replace("\"read\"", "\"admin\"")),
            16,
            "`read` or `write`",
        ),
        (
            with_opcua(&OPCUA.replace("\"viewer\"", "\"operator\"")),
            14,
            "once",
        ),
        (
            with_opcua(&OPCUA.replace("\"viewer\"", "\"a b\"")),
            14,
            "without spaces",
        ),
    ];
    for (text, line, why) in cases {
        let error = refused(&text);
        assert_eq!(error.line, Some(line), "{why}: {error}");
        assert!(error.to_string().contains(why), "{why}: {error}");
    }
    let unknown = refused(&with_opcua(&OPCUA.replace("pki_dir", "pki_folder")));
    assert!(matches!(unknown.kind, GatewayFileErrorKind::Syntax(_)));
}
