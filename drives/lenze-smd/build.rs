//! Generates the crate's API from `descriptions/lenze-smd` at build time.

fn main() {
    if let Err(error) = drivegen::Builder::new("descriptions/lenze-smd").compile() {
        eprintln!("{error}");
        std::process::exit(1);
    }
}
