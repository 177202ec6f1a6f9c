//! The Kinco FD manual's RS-232 request telegrams (section 9.4, lines 2330-2365), as listed in
//! `tests/fixtures/kinco-rs232/manual-telegrams.txt`: read once here for the three tests that
//! check them (the codec in drivebus, the generated API in tests/, the shipped kinco-fd crate).

/// Each telegram the manual prints, as `(manual line, bytes)`, in the order of the list.
pub fn printed() -> Vec<(u32, Vec<u8>)> {
    let path = crate::workspace_root().join("tests/fixtures/kinco-rs232/manual-telegrams.txt");
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|error| panic!("{}: {error}", path.display()));
    text.lines()
        .filter(|line| !line.starts_with('#') && !line.trim().is_empty())
        .map(|line| {
            let (number, hex) = line
                .split_once(' ')
                .unwrap_or_else(|| panic!("no bytes after the line number: {line:?}"));
            let number = number
                .parse()
                .unwrap_or_else(|_| panic!("not a manual line number: {line:?}"));
            (number, bytes(hex))
        })
        .collect()
}

/// Bytes written as hex pairs separated by spaces.
pub fn bytes(hex: &str) -> Vec<u8> {
    hex.split_whitespace()
        .map(|pair| {
            u8::from_str_radix(pair, 16).unwrap_or_else(|_| panic!("not a hex byte: {pair:?}"))
        })
        .collect()
}
