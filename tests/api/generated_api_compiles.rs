//! The promise that mistakes do not compile, proven with trybuild: every case in
//! `compile/fail/` must fail with the committed `.stderr`. Its counterpart in `compile/pass/`
//! (the same code, done right) builds and runs as a test of `compile_pass.rs`, so trybuild only
//! checks (a pass case would make it build and link every case and its dependencies a second
//! time). Re-bless with `TRYBUILD=overwrite`.

#[test]
fn mistakes_do_not_compile() {
    trybuild::TestCases::new().compile_fail("compile/fail/*.rs");
}

#[test]
fn every_failing_case_has_a_passing_counterpart() {
    let names = |dir: &str| -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.ends_with(".rs"))
            .collect();
        names.sort();
        names
    };
    let (fail, pass) = (names("compile/fail"), names("compile/pass"));
    assert!(
        fail.len() >= 12,
        "the suite has {} cases; the contract asks for at least 12",
        fail.len()
    );
    assert_eq!(
        fail, pass,
        "each compile-fail case needs a compile-pass case of the same name"
    );
}
