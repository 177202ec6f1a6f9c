//! Generates the RS-232 test fixture's drive API (`tests/fixtures/kinco-rs232`) for the
//! compile-fail suite and the pty tests, and the module list of the compile-pass cases
//! (`api/compile_pass.rs`).

use std::fmt::Write as _;
use std::path::Path;

fn main() {
    if let Err(error) = drivegen::Builder::new("fixtures/kinco-rs232")
        .file_name("kinco_rs232.rs")
        .compile()
    {
        eprintln!("{error}");
        std::process::exit(1);
    }
    if let Err(error) = write_pass_cases() {
        eprintln!("compile/pass: {error}");
        std::process::exit(1);
    }
}

/// One module per `compile/pass/*.rs`, holding the case and a test that runs its `main`: the
/// cases build with the tests' own dependencies, so trybuild only checks the failing half.
fn write_pass_cases() -> std::io::Result<()> {
    println!("cargo:rerun-if-changed=compile/pass");
    let dir =
        Path::new(&std::env::var("CARGO_MANIFEST_DIR").expect("set by cargo")).join("compile/pass");
    let mut names: Vec<String> = std::fs::read_dir(&dir)?
        .filter_map(|entry| entry.ok()?.file_name().into_string().ok())
        .filter_map(|name| name.strip_suffix(".rs").map(str::to_owned))
        .collect();
    names.sort();
    let mut modules = String::new();
    for name in &names {
        let path = dir.join(format!("{name}.rs"));
        writeln!(
            modules,
            "mod {name} {{\n    include!({path:?});\n    #[test]\n    fn compiles_and_runs() {{\n        main()\n    }}\n}}"
        )
        .expect("writing to a String");
    }
    let out = Path::new(&std::env::var("OUT_DIR").expect("set by cargo")).join("compile_pass.rs");
    std::fs::write(out, modules)
}
