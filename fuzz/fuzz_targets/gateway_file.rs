//! The gateway file reader (`drivegen::gateway_file::parse`) fed arbitrary text. Asserts that
//! it never panics, that a file it accepts has at least one drive, drive names that are one
//! topic level each once, a polling interval of at least 1 ms (at most 65535 by event timer),
//! `pdo_start` only with `pdo`, lines within the text, an endpoint (MQTT or OPC UA, whose users
//! are named once and who someone can log in as), and that a refusal's line is within the text.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let lines = u32::try_from(text.lines().count().max(1) + 1).unwrap_or(u32::MAX);
    let within = |line: u32| line >= 1 && line <= lines;
    match drivegen::gateway_file::parse(text) {
        Ok(file) => {
            assert!(!file.drives.is_empty());
            assert!(file.mqtt.is_some() || file.opcua.is_some());
            assert!(file.mqtt.as_ref().is_none_or(|mqtt| mqtt.port != 0));
            if let Some(opcua) = &file.opcua {
                assert!(opcua.port != 0 && opcua.sampling_interval_ms >= 1);
                assert!(opcua.anonymous || !opcua.users.is_empty());
                assert!(within(opcua.line));
                for (i, user) in opcua.users.iter().enumerate() {
                    assert!(!user.name.is_empty() && within(user.line));
                    assert!(opcua.users[..i].iter().all(|u| u.name != user.name));
                }
            }
            for (i, drive) in file.drives.iter().enumerate() {
                assert!(!drive.name.is_empty());
                assert!(!drive.name.contains(['/', '+', '#']));
                assert!(file.drives[..i].iter().all(|d| d.name != drive.name));
                assert!(drive.interval_ms >= 1);
                assert!(drive.pdo.on() || !drive.pdo_start);
                // The event timer holds 16 bits of milliseconds.
                let event = drive.pdo == drivegen::gateway_file::PdoUse::Event;
                assert!(!event || drive.interval_ms <= u32::from(u16::MAX));
                assert!(!drive.parameters.is_empty());
                assert!(within(drive.line));
                assert!(drive.bus.iter().all(|o| within(o.line)));
                assert!(drive.parameters.iter().chain(&drive.writable).all(|n| within(n.line)));
            }
        }
        Err(error) => {
            if let Some(line) = error.line {
                assert!(within(line), "line {line} of {lines}");
            }
            let _ = error.to_string();
        }
    }
});
