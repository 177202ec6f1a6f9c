//! The promise that mistakes do not compile, proven with trybuild: every case in
//! `compile/fail/` must fail with the committed `.stderr`, and its counterpart in `compile/pass/`
//! (the same code, done right) must build. Re-bless with `TRYBUILD=overwrite`.

#[test]
fn mistakes_do_not_compile_and_their_fixes_do() {
    let cases = trybuild::TestCases::new();
    cases.compile_fail("compile/fail/*.rs");
    cases.pass("compile/pass/*.rs");
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
