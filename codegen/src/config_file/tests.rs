use super::*;

fn sample() -> ConfigFile {
    ConfigFile {
        description: DescriptionRef {
            name: "lafert_smartris".into(),
            firmware: Some("2.42".into()),
            path: Some("/x/descriptions/lafert-smartris".into()),
        },
        drive: DriveRecord {
            target: "Modbus TCP 127.0.0.1:502 unit 1".into(),
            variant: None,
            pulled_at: "2026-11-27T21:40:00Z".into(),
        },
        identity: vec![IdentityEntry {
            name: "fw_release".into(),
            raw: 242,
            line: 0,
        }],
        parameters: vec![
            SavedParameter {
                name: "speed_ramp_up".into(),
                value: "1500 rpm/s".into(),
                raw: SavedRaw::Int(1500),
                unit: Some("rpm/s".into()),
                line: 0,
            },
            SavedParameter {
                name: "huge".into(),
                value: "18446744073709551615".into(),
                raw: SavedRaw::Int(i128::from(u64::MAX)),
                unit: None,
                line: 0,
            },
            SavedParameter {
                name: "label".into(),
                value: "a\"b".into(),
                raw: SavedRaw::Bytes(vec![97, 34, 98]),
                unit: None,
                line: 0,
            },
        ],
        unread: vec![Unread {
            name: "max_current".into(),
            reason: "no answer (timeout)".into(),
            line: 0,
        }],
    }
}

/// The lines `render` puts each entry on, for comparing with a parsed file.
fn with_lines(mut file: ConfigFile, text: &str) -> ConfigFile {
    let line = |name: &str| {
        let at = text
            .lines()
            .position(|l| l.starts_with(&format!("{name} = ")));
        at.map_or(0, |i| i as u32 + 1)
    };
    file.identity
        .iter_mut()
        .for_each(|e| e.line = line(&e.name));
    file.parameters
        .iter_mut()
        .for_each(|p| p.line = line(&p.name));
    file.unread.iter_mut().for_each(|u| u.line = line(&u.name));
    file
}

#[test]
fn a_rendered_file_reads_back_the_same_with_lines() {
    let text = render(&sample());
    let parsed = parse(&text).unwrap();
    assert_eq!(parsed, with_lines(sample(), &text));
    assert!(parsed.parameters.iter().all(|p| p.line > 0));
}

#[test]
fn a_truncated_file_is_refused_with_a_line_or_what_is_missing() {
    let text = render(&sample());
    let cut = &text[..text.find("huge = { value").unwrap() + 20];
    let error = parse(cut).unwrap_err();
    assert!(
        matches!(error.kind, ConfigFileErrorKind::Syntax(_)),
        "{error}"
    );
    assert!(error.line.is_some(), "{error}");
    let before_drive = &text[..text.find("[drive]").unwrap()];
    let error = parse(before_drive).unwrap_err();
    assert_eq!(error.kind, ConfigFileErrorKind::Missing("[drive]"));
}

#[test]
fn a_bad_entry_points_at_its_line() {
    let text = render(&sample()).replace("raw = 1500", "raw = \"lots\"");
    let error = parse(&text).unwrap_err();
    let line = text
        .lines()
        .position(|l| l.starts_with("speed_ramp_up"))
        .unwrap() as u32
        + 1;
    assert_eq!(error.line, Some(line));
    assert!(
        error
            .to_string()
            .contains("`speed_ramp_up`: expected a `raw`"),
        "{error}"
    );
}

#[test]
fn another_format_version_is_refused() {
    let text = render(&sample()).replace("format = 1", "format = 2");
    let error = parse(&text).unwrap_err();
    assert_eq!(error.kind, ConfigFileErrorKind::UnsupportedFormat(2));
    assert_eq!(error.line, Some(4));
}

#[test]
fn a_parameter_both_saved_and_unread_is_refused() {
    let text = render(&sample()).replace("max_current = ", "speed_ramp_up = ");
    let error = parse(&text).unwrap_err();
    assert_eq!(
        error.kind,
        ConfigFileErrorKind::Duplicate("speed_ramp_up".into())
    );
}

/// The fuzz target's property (fuzz/fuzz_targets/config_file.rs) over every prefix of a file:
/// no panic, and a file read renders to text that reads back to the same rendering.
#[test]
fn every_prefix_of_a_file_is_read_or_refused_without_panic() {
    let text = render(&sample());
    for end in (0..=text.len()).filter(|i| text.is_char_boundary(*i)) {
        if let Ok(file) = parse(&text[..end]) {
            let rendered = render(&file);
            assert_eq!(render(&parse(&rendered).unwrap()), rendered, "prefix {end}");
        }
    }
}

#[test]
fn names_that_are_not_bare_keys_are_quoted() {
    let mut file = sample();
    file.parameters[0].name = "two words".into();
    let text = render(&file);
    assert!(text.contains("\"two words\" = { value"), "{text}");
    assert_eq!(parse(&text).unwrap().parameters[0].name, "two words");
}
