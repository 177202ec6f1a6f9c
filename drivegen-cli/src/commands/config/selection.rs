//! Which parameters make up a drive's configuration: readable and writable ones, without the
//! writes that act rather than set (commands, stops, the lock's own command and grants, the
//! state machine's command word and setpoint), and which of them are modes that others are set
//! after.

use drivegen::ir::{Device, Parameter, Scale};

/// CiA 402 modes of operation: the mode the drive's other objects are used in.
const MODES_OF_OPERATION: u16 = 0x6060;

/// Whether `parameter` belongs in a configuration backup.
pub fn is_configuration(device: &Device, parameter: &Parameter) -> bool {
    let readable = parameter.readable_over_modbus()
        || parameter.readable_over_canopen()
        || parameter.readable_over_rs232();
    let acts = parameter.command.is_some()
        || parameter.stops.is_some()
        || device
            .lock
            .as_ref()
            .is_some_and(|lock| lock.is_exempt(&parameter.name))
        || device.state_machine.as_ref().is_some_and(|machine| {
            machine.command == parameter.name
                || machine.setpoint.as_deref() == Some(parameter.name.as_str())
        });
    readable && parameter.is_writable() && !acts
}

/// The configuration parameters of `device`, in its order.
pub fn configuration(device: &Device) -> Vec<&Parameter> {
    device
        .parameters
        .iter()
        .filter(|p| is_configuration(device, p))
        .collect()
}

/// Whether `parameter` is a mode: a value that decides what other parameters mean or whether
/// they may be written, so it is written first. The variant selector, a parameter an unlock
/// requires, a parameter a state's status depends on, and the CiA 402 mode of operation.
pub fn is_mode(device: &Device, parameter: &Parameter) -> bool {
    let name = parameter.name.as_str();
    let selects_variant = device
        .variant_selection()
        .is_some_and(|(selector, _)| selector.name == name);
    let required_by_unlock = device.lock.as_ref().is_some_and(|lock| {
        lock.unlocks
            .iter()
            .any(|u| u.requires.as_ref().is_some_and(|r| r.parameter == name))
    });
    let conditions_a_state = device.state_machine.as_ref().is_some_and(|machine| {
        machine
            .states
            .iter()
            .flat_map(|s| &s.status)
            .any(|pattern| pattern.when.as_ref().is_some_and(|c| c.parameter == name))
    });
    let cia402_mode = parameter
        .canopen
        .iter()
        .any(|a| a.index == MODES_OF_OPERATION && a.subindex == 0);
    selects_variant || required_by_unlock || conditions_a_state || cia402_mode
}

/// The parameters whose current values `parameter`'s value is checked against or scaled by:
/// they are written before it.
pub fn depends_on(parameter: &Parameter) -> Vec<&str> {
    let mut names: Vec<&str> = parameter
        .bounds
        .as_ref()
        .map(|b| b.names().collect())
        .unwrap_or_default();
    if let Some(Scale::Runtime { inputs, .. }) = &parameter.scale {
        names.extend(inputs.iter().map(String::as_str));
    }
    names
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A shipped description, loaded.
    pub fn shipped(name: &str) -> Device {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../descriptions")
            .join(name);
        drivegen::check(&path)
            .device
            .expect("a shipped description is valid")
    }

    fn names(device: &Device) -> Vec<&str> {
        configuration(device)
            .iter()
            .map(|p| p.name.as_str())
            .collect()
    }

    #[test]
    fn commands_stops_grants_and_setpoints_are_not_configuration() {
        let lafert = shipped("lafert-smartris");
        let saved = names(&lafert);
        assert!(saved.contains(&"speed_ramp_up"));
        for acting in ["control_word", "speed_setpoint", "store_all_parameters"] {
            assert!(!saved.contains(&acting), "{acting}");
        }
        let lenze = shipped("lenze-smd");
        let saved = names(&lenze);
        assert!(saved.contains(&"user_password"));
        for acting in [
            "unlock_parameters",
            "unlock_commands",
            "lock_security",
            "stop",
            "load_lenze_setting",
        ] {
            assert!(!saved.contains(&acting), "{acting}");
        }
    }

    #[test]
    fn modes_are_what_others_depend_on() {
        let lenze = shipped("lenze-smd");
        let mode = |name: &str| is_mode(&lenze, lenze.parameter(name).unwrap());
        assert!(mode("control_source"), "an unlock requires it");
        assert!(!mode("acceleration_time"));
        let kinco = shipped("kinco-fd");
        assert!(is_mode(
            &kinco,
            kinco.parameter("modes_of_operation").unwrap()
        ));
    }
}
