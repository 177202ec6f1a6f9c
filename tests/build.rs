//! Generates the RS-232 test fixture's drive API (`tests/fixtures/kinco-rs232`) for the
//! compile-fail suite and the pty tests.

fn main() {
    if let Err(error) = drivegen::Builder::new("fixtures/kinco-rs232")
        .file_name("kinco_rs232.rs")
        .compile()
    {
        eprintln!("{error}");
        std::process::exit(1);
    }
}
