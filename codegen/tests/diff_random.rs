//! `drivegen diff` over random valid descriptions: a description compared with itself has no
//! change; removing a parameter (not mapped in a PDO) is one breaking change naming it, and adding
//! it back is one compatible change.

mod support;

use drivegen::diff::{diff, Impact};
use proptest::prelude::*;
use support::random_description::description;
use support::Scratch;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn diffs_name_exactly_what_changed(text in description(), pick in any::<prop::sample::Index>()) {
        let scratch = Scratch::new("diff-random");
        let path = scratch.0.join("device.toml");
        std::fs::write(&path, &text).unwrap();
        let Some(device) = drivegen::check(&path).device else {
            return Ok(());
        };
        prop_assert_eq!(diff(&device, &device), vec![]);
        let mapped = |name: &str| device.pdos().any(|(m, _)| m.entries.iter().any(|e| e == name));
        let removable: Vec<usize> = (0..device.parameters.len())
            .filter(|&i| !mapped(&device.parameters[i].name))
            .collect();
        if removable.is_empty() {
            return Ok(());
        }
        let mut smaller = device.clone();
        let removed = smaller.parameters.remove(removable[pick.index(removable.len())]);
        let subject = format!("parameter `{}`", removed.name);
        let removal = diff(&device, &smaller);
        prop_assert_eq!(removal.len(), 1, "{:?}", removal);
        prop_assert_eq!((removal[0].impact, &removal[0].subject), (Impact::Breaking, &subject));
        let addition = diff(&smaller, &device);
        prop_assert_eq!(addition.len(), 1, "{:?}", addition);
        prop_assert_eq!((addition[0].impact, &addition[0].subject), (Impact::Compatible, &subject));
    }
}
