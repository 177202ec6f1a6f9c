//! The Kinco position example homes the simulated drive and reaches each of its three positions
//! within the position window.

mod support;

#[test]
fn homes_and_reaches_three_positions() {
    let stdout = support::run("kinco_position");
    assert!(
        stdout.contains("homed (method 17, offset 1000 inc): position -1000 inc"),
        "{stdout}"
    );
    for target in ["50000", "-20000", "120000"] {
        let line = format!("moved to {target:>8} inc: position {target:>8} inc, error 0 inc");
        assert!(stdout.contains(&line), "{line}\n{stdout}");
    }
}
