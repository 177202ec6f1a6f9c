//! Bad TOML descriptions never panic the tool chain: random valid descriptions with lines
//! deleted, repeated or swapped and values replaced by hostile ones (huge, negative, NaN,
//! infinite, wrong kinds) are checked into diagnostics, and whatever device still checks valid is
//! generated, exported as an EDS and diffed without a panic.

mod support;

use proptest::prelude::*;
use support::random_description::description;
use support::Scratch;

/// Values that no key expects, or not in this range.
const HOSTILE: &[&str] = &[
    "-1",
    "0",
    "99999999999999999999",
    "-9223372036854775808",
    "1e400",
    "nan",
    "-inf",
    "0.1",
    "\"\"",
    "\"x\"",
    "\"$NODEID+0x180\"",
    "\"1/0\"",
    "\"0/0\"",
    "{ expr = \"1 / 0\" }",
    "{ expr = \"(\" }",
    "[]",
    "[1, \"a\"]",
    "{}",
    "true",
    "\"\u{221e}\"",
];

/// One edit of the description's lines.
#[derive(Debug, Clone)]
enum Edit {
    Delete(prop::sample::Index),
    Repeat(prop::sample::Index),
    Swap(prop::sample::Index, prop::sample::Index),
    Replace(prop::sample::Index, &'static str),
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        any::<prop::sample::Index>().prop_map(Edit::Delete),
        any::<prop::sample::Index>().prop_map(Edit::Repeat),
        (any::<prop::sample::Index>(), any::<prop::sample::Index>())
            .prop_map(|(a, b)| Edit::Swap(a, b)),
        (any::<prop::sample::Index>(), prop::sample::select(HOSTILE))
            .prop_map(|(at, value)| Edit::Replace(at, value)),
    ]
}

/// `text` with `edits` applied to its lines.
fn edited(text: &str, edits: &[Edit]) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    for edit in edits {
        if lines.is_empty() {
            break;
        }
        let len = lines.len();
        match edit {
            Edit::Delete(at) => {
                lines.remove(at.index(len));
            }
            Edit::Repeat(at) => {
                let line = lines[at.index(len)].clone();
                lines.insert(at.index(len), line);
            }
            Edit::Swap(a, b) => lines.swap(a.index(len), b.index(len)),
            Edit::Replace(at, value) => {
                let line = &mut lines[at.index(len)];
                if let Some(eq) = line.find(" = ") {
                    line.replace_range(eq + 3.., value);
                }
            }
        }
    }
    lines.join("\n")
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn edited_descriptions_never_panic(
        text in description(),
        edits in proptest::collection::vec(edit(), 1..4),
    ) {
        let scratch = Scratch::new("descriptions-never-panic");
        let path = scratch.0.join("device.toml");
        std::fs::write(&path, edited(&text, &edits)).unwrap();
        let checked = drivegen::check(&path);
        let _ = checked.render();
        if let Some(device) = checked.device {
            drivegen::emit::rust::generate(&device, "edited");
            if device.parameters.iter().any(|p| !p.canopen.is_empty()) {
                drivegen::eds::export(&device);
            }
            prop_assert!(drivegen::diff::diff(&device, &device).is_empty());
        }
    }
}
