//! The candump line parser fed arbitrary lines (a candump log or `candump -L` stream).
//!
//! Input: one line. Asserts that a parsed frame formats to compact text that parses to the same
//! frame, that a parsed timestamp survives the fields around it, and that the reader gives the
//! same records from the input read as a whole and through a buffer of 7 bytes (a line parsed
//! where it lies in the buffer, or copied across the buffer's end).
#![no_main]

use std::io::BufReader;

use drivebus::canopen::can::candump::{format_frame, parse_frame, parse_line, CandumpReader};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|line: &[u8]| {
    let whole: Vec<_> = CandumpReader::new(line).collect();
    let small: Vec<_> = CandumpReader::new(BufReader::with_capacity(7, line)).collect();
    assert_eq!(whole, small, "records through a small buffer");
    let Ok(Some(record)) = parse_line(line) else {
        return;
    };
    let mut text = Vec::new();
    format_frame(&record.frame, &mut text);
    assert_eq!(
        parse_frame(&text),
        Ok(record.frame),
        "compact form {text:?}"
    );
    let mut logged = Vec::new();
    if let Some(us) = record.timestamp_us {
        logged.extend(format!("({}.{:06}) can0 ", us / 1_000_000, us % 1_000_000).bytes());
    }
    logged.extend(&text);
    assert_eq!(parse_line(&logged), Ok(Some(record)), "log line {logged:?}");
});
