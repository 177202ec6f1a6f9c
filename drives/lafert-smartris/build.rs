//! Generates the crate's API from `descriptions/lafert-smartris` at build time.

fn main() {
    if let Err(error) = drivegen::Builder::new("descriptions/lafert-smartris").compile() {
        eprintln!("{error}");
        std::process::exit(1);
    }
}
