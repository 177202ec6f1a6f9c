//! The network file reader (`drivegen::network_file::parse`) fed arbitrary text. Asserts that
//! it never panics, that a file it accepts has at least one node, node ids 1-127 each once,
//! PDO numbers 1-512 and 11-bit COB-IDs, and lines within the text, and that a refusal's line
//! is within the text.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let lines = u32::try_from(text.lines().count().max(1) + 1).unwrap_or(u32::MAX);
    match drivegen::network_file::parse(text) {
        Ok(file) => {
            assert!(!file.nodes.is_empty());
            let mut seen = [false; 128];
            for node in &file.nodes {
                assert!((1..=127).contains(&node.id));
                assert!(!std::mem::replace(&mut seen[usize::from(node.id)], true));
                assert!(node.line >= 1 && node.line <= lines);
                assert!(node.parameters.iter().all(|p| p.line >= 1 && p.line <= lines));
                for pdo in &node.pdos {
                    assert!((1..=512).contains(&pdo.number));
                    assert!(pdo.cob_id.is_none_or(|c| c & !0x4000_0000 <= 0x7FF));
                    assert!(pdo.line >= 1 && pdo.line <= lines);
                    assert!(pdo.mapping.iter().all(|m| m.line >= 1 && m.line <= lines));
                }
            }
        }
        Err(error) => {
            if let Some(line) = error.line {
                assert!(line >= 1 && line <= lines, "line {line} of {lines}");
            }
            let _ = error.to_string();
        }
    }
});
