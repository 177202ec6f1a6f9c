//! `drivegen dbc export` checked by an independent reader: cantools loads each exported DBC and
//! decodes PDO frames to the same values `drivegen decode` gives them from the description
//! (`tests/peers/dbc_decode.py`; run `tests/peers/setup.sh` or set `DRIVEGEN_PYTHON`).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use peer_support::python;
use serde_json::Value;

const BIN: &str = env!("CARGO_BIN_EXE_drivegen");
const NODE_ID: &str = "5";

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn succeeded(output: Output, what: &str) -> String {
    assert!(
        output.status.success(),
        "{what}: {}{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout).unwrap()
}

fn drivegen(args: &[&str]) -> String {
    let output = Command::new(BIN)
        .args(args)
        .current_dir(root())
        .output()
        .unwrap();
    succeeded(output, &format!("drivegen {args:?}"))
}

/// `(id, length)` of each `BO_` line of a DBC.
fn messages(dbc: &str) -> Vec<(u32, usize)> {
    dbc.lines()
        .filter_map(|l| l.strip_prefix("BO_ "))
        .map(|l| {
            let mut fields = l.split_whitespace();
            let id = fields.next().unwrap().parse().unwrap();
            let length = fields.nth(1).unwrap().parse().unwrap();
            (id, length)
        })
        .collect()
}

/// A candump capture with two frames per message: payload bytes that differ by message and
/// position (so every signal sees a value of its own), then every byte 3 (a mode value both
/// readers name, e.g. CiA 402 profile velocity).
fn capture(messages: &[(u32, usize)]) -> String {
    let frame = |m: usize, id: u32, payload: String| {
        format!("(1700000000.{m:06}) can0 {id:03X}#{payload}\n")
    };
    let mixed = messages.iter().enumerate().map(|(m, &(id, length))| {
        let payload = (0..length).map(|i| format!("{:02X}", (m * 37 + i * 101 + 11) % 256));
        frame(m, id, payload.collect())
    });
    let threes = messages
        .iter()
        .enumerate()
        .map(|(m, &(id, length))| frame(messages.len() + m, id, "03".repeat(length)));
    mixed.chain(threes).collect()
}

/// `name=value` pairs of each PDO line of `drivegen decode --json`, in frame order.
fn drivegen_values(decoded: &str) -> Vec<BTreeMap<String, String>> {
    decoded
        .lines()
        .map(|l| serde_json::from_str::<Value>(l).unwrap())
        .map(|line| {
            let value = line["value"].as_str().unwrap_or_default();
            value
                .split(", ")
                .filter_map(|pair| pair.split_once('='))
                .map(|(name, value)| (name.to_owned(), value.to_owned()))
                .collect()
        })
        .collect()
}

/// What cantools and drivegen agree on: (numbers, names) compared.
fn compare(description: &str, dir: &Path) -> (usize, usize) {
    let dbc = dir.join(format!("{description}.dbc"));
    let log = dir.join(format!("{description}.log"));
    drivegen(&[
        "dbc",
        "export",
        &format!("descriptions/{description}"),
        "--node-id",
        NODE_ID,
        "-o",
        dbc.to_str().unwrap(),
    ]);
    let frames = messages(&std::fs::read_to_string(&dbc).unwrap());
    assert!(!frames.is_empty(), "{description}: no message");
    std::fs::write(&log, capture(&frames)).unwrap();
    let ours = drivegen_values(&drivegen(&[
        "decode",
        &format!("descriptions/{description}"),
        log.to_str().unwrap(),
        "--json",
    ]));
    let script = root().join("tests/peers/dbc_decode.py");
    let theirs = Command::new(python())
        .arg(script)
        .arg(&dbc)
        .arg(&log)
        .output()
        .expect("python with cantools: run tests/peers/setup.sh");
    let theirs = succeeded(theirs, "cantools");
    let mut compared = (0, 0);
    for (frame, (line, ours)) in theirs.lines().zip(&ours).enumerate() {
        let line: Value = serde_json::from_str(line).unwrap();
        let signals = line["signals"]
            .as_object()
            .expect("cantools knows the frame");
        for (name, value) in signals {
            let Some(text) = ours.get(name) else {
                panic!("{description} frame {frame}: drivegen decoded no {name}: {ours:?}");
            };
            match value {
                Value::String(named) => {
                    assert_eq!(text, named, "{description} frame {frame} {name}");
                    compared.1 += 1;
                }
                number => {
                    let number = number.as_f64().unwrap();
                    // Flags show as names in drivegen; a number is its first word.
                    let Some(shown) = text.split(' ').next().and_then(|w| w.parse::<f64>().ok())
                    else {
                        continue;
                    };
                    let tolerance = 1e-6 * number.abs().max(1.0);
                    assert!(
                        (shown - number).abs() <= tolerance,
                        "{description} frame {frame} {name}: drivegen {text}, cantools {number}"
                    );
                    compared.0 += 1;
                }
            }
        }
    }
    assert_eq!(theirs.lines().count(), 2 * frames.len(), "{description}");
    assert_eq!(ours.len(), 2 * frames.len(), "{description}");
    compared
}

#[test]
fn cantools_decodes_the_exported_pdos_as_drivegen_does() {
    let dir = std::env::temp_dir().join(format!("drivegen-dbc-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut total = (0, 0);
    for description in ["kinco-fd", "lafert-smartris", "ezwheel-swd"] {
        let (numbers, names) = compare(description, &dir);
        assert!(numbers > 0, "{description}: no number compared");
        total = (total.0 + numbers, total.1 + names);
    }
    assert!(total.1 > 0, "no enumerated value compared");
    std::fs::remove_dir_all(&dir).unwrap();
}
