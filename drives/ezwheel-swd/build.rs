//! Generates the crate's API from `descriptions/ezwheel-swd` at build time.

fn main() {
    if let Err(error) = drivegen::Builder::new("descriptions/ezwheel-swd").compile() {
        eprintln!("{error}");
        std::process::exit(1);
    }
}
