//! The CSP example runs two simulated axes along one trajectory (a short 0.5 s move at a 4 ms
//! SYNC): both pass the middle together and end standing within the following error window of
//! the end.

mod support;

#[test]
fn two_axes_follow_one_trajectory_to_its_end() {
    let stdout = support::run_with("csp_two_axes", &["0.5"]);
    let moving: Vec<&str> = stdout.lines().filter(|l| l.starts_with("t = ")).collect();
    assert!(moving.len() >= 5, "{stdout}");
    for line in &moving {
        // "t =  0.20 s: axis 1 at   6436 inc, axis 2 at   6436 inc"
        let numbers: Vec<i64> = line
            .split(|c: char| !c.is_ascii_digit() && c != '-')
            .filter_map(|w| w.parse().ok())
            .collect();
        let (a, b) = (numbers[numbers.len() - 3], numbers[numbers.len() - 1]);
        assert!((a - b).abs() <= 2_000, "the axes apart: {line}");
    }
    for axis in [1, 2] {
        let line = stdout
            .lines()
            .find(|l| l.starts_with(&format!("axis {axis} holds")))
            .unwrap_or_else(|| panic!("axis {axis}: {stdout}"));
        let error: i64 = line
            .split("error ")
            .nth(1)
            .and_then(|rest| rest.split(' ').next())
            .and_then(|n| n.parse().ok())
            .unwrap_or_else(|| panic!("{line}"));
        assert!(error.abs() <= 2_000, "{line}");
        let holds: i64 = line.split(' ').nth(3).unwrap().parse().unwrap();
        assert_eq!(holds - error, 20_000, "the end of the trajectory: {line}");
    }
}
