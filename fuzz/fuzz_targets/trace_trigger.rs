//! The trace trigger (`drivegen trace --trigger`) and its window fed arbitrary input.
//!
//! Input: a first line that is the trigger text, then events of 4 bytes each (kind, node, value
//! as i16). Asserts that parsing never panics, and that every captured window keeps at most `pre`
//! events before and `post` after its trigger, exactly `post` when it is complete.
#![no_main]

use drivebus::trace::{Event, Trigger, Window};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let split = bytes.iter().position(|&b| b == b'\n').unwrap_or(bytes.len());
    let Ok(text) = std::str::from_utf8(&bytes[..split]) else {
        return;
    };
    let Ok(trigger) = text.parse::<Trigger>() else {
        return;
    };
    let events = bytes.get(split + 1..).unwrap_or_default();
    let (pre, post) = (text.len() % 5, events.len() % 7);
    let mut armed = trigger.arm();
    let mut window = Window::new(pre, post);
    let mut captured = Vec::new();
    for chunk in events.chunks_exact(4) {
        let value = f64::from(i16::from_le_bytes([chunk[2], chunk[3]]));
        let event = match chunk[0] % 4 {
            0 => Event::Sample {
                node: chunk[1],
                parameter: text.split(['>', '<']).next().unwrap_or_default().trim(),
                value,
            },
            1 => Event::Emcy {
                node: chunk[1],
                code: value as u16,
            },
            2 => Event::State {
                node: chunk[1],
                state: chunk[3],
            },
            _ => Event::NmtCommand {
                node: Some(chunk[1]),
            },
        };
        let fired = armed.fires(&event);
        captured.extend(window.push(chunk[1], fired));
    }
    captured.extend(window.finish());
    for c in captured {
        assert!(c.before.len() <= pre && c.after.len() <= post);
        assert!(!c.complete || c.after.len() == post);
    }
});
