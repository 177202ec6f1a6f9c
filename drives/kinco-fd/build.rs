//! Generates the crate's API from `descriptions/kinco-fd` at build time.

fn main() {
    if let Err(error) = drivegen::Builder::new("descriptions/kinco-fd").compile() {
        eprintln!("{error}");
        std::process::exit(1);
    }
}
