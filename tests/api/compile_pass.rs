//! The passing half of the compile-fail suite: each `compile/pass/*.rs` (the same code as its
//! `compile/fail/` counterpart, done right) is a module here, built with the tests and its
//! `main` run as a test. trybuild (`generated_api_compiles.rs`) checks the failing half only, so
//! it needs no second build of the drive crates.

include!(concat!(env!("OUT_DIR"), "/compile_pass.rs"));
