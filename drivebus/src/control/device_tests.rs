//! The device side of CiA 402: the statusword of every state, every commanded transition of the
//! table, the command table's two compound rows and the quick stop options.

use super::*;
use crate::control::quirks::Quirk;

/// The decided statuswords (module documentation), written out rather than computed.
const STATUSWORDS: [(State, u16); 8] = [
    (State::NotReadyToSwitchOn, 0x0000),
    (State::SwitchOnDisabled, 0x0040),
    (State::ReadyToSwitchOn, 0x0021),
    (State::SwitchedOn, 0x0033),
    (State::OperationEnabled, 0x0037),
    (State::QuickStopActive, 0x0017),
    (State::FaultReactionActive, 0x001F),
    (State::Fault, 0x0008),
];

#[test]
fn every_state_reports_its_decided_statusword_which_decodes_to_it() {
    for (state, word) in STATUSWORDS {
        let device = Cia402Device::in_state(state);
        assert_eq!(device.statusword(), word, "{state}");
        assert_eq!(State::decode(word), Some(state), "{word:#06x}");
    }
}

#[test]
fn voltage_enabled_shows_while_the_high_level_power_is_on() {
    for (state, word) in STATUSWORDS {
        let powered = matches!(
            state,
            State::SwitchedOn
                | State::OperationEnabled
                | State::QuickStopActive
                | State::FaultReactionActive
        );
        assert_eq!(word & VOLTAGE_ENABLED_BIT != 0, powered, "{state}");
    }
}

#[test]
fn remote_shows_only_on_a_drive_that_honours_it_while_the_controlword_is_processed() {
    let honours = Quirks::STANDARD.with(Quirk::HonoursRemote);
    for (state, word) in STATUSWORDS {
        assert_eq!(word & REMOTE_BIT, 0, "{state}");
        let remote = Cia402Device::in_state(state)
            .with_quirks(honours)
            .statusword();
        let processed = state != State::NotReadyToSwitchOn;
        assert_eq!(remote & REMOTE_BIT != 0, processed, "{state}");
        assert_eq!(remote & !REMOTE_BIT, word, "{state}");
    }
}

#[test]
fn the_quirk_for_transition_16_gives_it_until_an_option_code_is_set() {
    let quirks = Quirks::STANDARD.with(Quirk::QuickStopToOperationEnabled);
    let mut device = Cia402Device::in_state(State::QuickStopActive).with_quirks(quirks);
    assert_eq!(device.quick_stop_option(), QuickStopOption::StopAndResume);
    device.set_quick_stop_option(QuickStopOption::from_code(2));
    assert_eq!(device.write_controlword(0x0F), None);
}

#[test]
fn every_commanded_transition_of_the_table_is_taken_on_its_command() {
    for transition in TABLE.transitions {
        let TransitionKind::Command(value) = transition.kind else {
            continue;
        };
        let from = State::ALL[usize::from(transition.from)];
        let mut device =
            Cia402Device::in_state(from).with_quick_stop_option(QuickStopOption::StopAndResume);
        let taken = device.write_controlword(value);
        assert_eq!(taken.map(|t| t.name), Some(transition.name), "from {from}");
        assert_eq!(device.state().index(), transition.to, "{}", transition.name);
    }
}

#[test]
fn standard_controlwords_take_the_standard_transitions() {
    let mut device = Cia402Device::default();
    for (controlword, state) in [
        (0x06, State::ReadyToSwitchOn),
        (0x07, State::SwitchedOn),
        (0x0F, State::OperationEnabled),
        (0x07, State::SwitchedOn),
        (0x0F, State::OperationEnabled),
        (0x02, State::QuickStopActive),
        (0x0F, State::QuickStopActive),
        (0x06, State::QuickStopActive),
        (0x00, State::SwitchOnDisabled),
    ] {
        device.write_controlword(controlword);
        assert_eq!(device.state(), state, "after {controlword:#04x}");
        assert_eq!(State::decode(device.statusword()), Some(state));
    }
}

#[test]
fn enable_operation_in_ready_to_switch_on_is_transitions_3_and_4() {
    let mut device = Cia402Device::in_state(State::ReadyToSwitchOn);
    let last = device.write_controlword(0x0F);
    assert_eq!(last.map(|t| t.name), Some("4"));
    assert_eq!(device.statusword(), 0x0037);
}

#[test]
fn quick_stop_outside_operation_enabled_is_transitions_7_and_10() {
    for (from, name) in [(State::ReadyToSwitchOn, "7"), (State::SwitchedOn, "10")] {
        let mut device = Cia402Device::in_state(from);
        assert_eq!(device.write_controlword(0x02).map(|t| t.name), Some(name));
        assert_eq!(device.statusword(), 0x0040);
    }
}

#[test]
fn the_quick_stop_option_decides_where_a_quick_stop_leads() {
    let stopped = |option| {
        let mut device = Cia402Device::in_state(State::OperationEnabled)
            .with_quick_stop_option(option)
            .with_controlword(0x0F);
        device.write_controlword(0x02);
        device
    };
    let off = stopped(QuickStopOption::SwitchOff);
    assert_eq!(off.statusword(), 0x0040, "code 0: switched off at once");

    let mut ramp = stopped(QuickStopOption::StopThenSwitchOff);
    assert_eq!(ramp.statusword(), 0x0017, "codes 1-4: stopping");
    assert_eq!(ramp.tick().map(|t| t.name), Some("12"));
    assert_eq!(
        ramp.statusword(),
        0x0040,
        "codes 1-4: then switch on disabled"
    );

    let mut resume = stopped(QuickStopOption::StopAndResume);
    resume.tick();
    assert_eq!(resume.statusword(), 0x0017, "codes 5-8: stays");
    assert_eq!(resume.write_controlword(0x0F).map(|t| t.name), Some("16"));
    assert_eq!(resume.statusword(), 0x0037);

    let mut hold = stopped(QuickStopOption::StopAndHold);
    hold.tick();
    assert_eq!(hold.write_controlword(0x0F), None, "no transition 16");
    assert_eq!(
        hold.write_controlword(0x06),
        None,
        "no shutdown from quick stop"
    );
    assert_eq!(hold.write_controlword(0x00).map(|t| t.name), Some("12"));
}

#[test]
fn option_codes_and_quirks_map_to_their_groups() {
    use QuickStopOption::*;
    for (code, option) in [
        (-1, StopAndHold),
        (0, SwitchOff),
        (1, StopThenSwitchOff),
        (4, StopThenSwitchOff),
        (5, StopAndResume),
        (8, StopAndResume),
        (9, StopAndHold),
    ] {
        assert_eq!(QuickStopOption::from_code(code), option, "code {code}");
    }
    assert_eq!(QuickStopOption::from_quirks(Quirks::STANDARD), StopAndHold);
    let quirky = Quirks::STANDARD.with(Quirk::QuickStopToOperationEnabled);
    assert_eq!(QuickStopOption::from_quirks(quirky), StopAndResume);
}

#[test]
fn a_fault_passes_through_fault_reaction_active() {
    let mut device = Cia402Device::in_state(State::OperationEnabled);
    assert_eq!(device.raise_fault().map(|t| t.name), Some("13"));
    assert_eq!(device.statusword(), 0x001F);
    assert_eq!(device.raise_fault(), None, "already reacting");
    assert_eq!(device.tick().map(|t| t.name), Some("14"));
    assert_eq!(device.statusword(), 0x0008);
    assert_eq!(device.tick(), None);
}

#[test]
fn not_ready_to_switch_on_leaves_by_itself() {
    let mut device = Cia402Device::in_state(State::NotReadyToSwitchOn);
    assert_eq!(
        device.write_controlword(0x06),
        None,
        "communication not yet active"
    );
    assert_eq!(device.tick().map(|t| t.name), Some("1"));
    assert_eq!(device.statusword(), 0x0040);
}

#[test]
fn fault_reset_needs_a_rising_edge() {
    let mut device = Cia402Device::default();
    device.write_controlword(0x80);
    device.raise_fault();
    device.tick();
    device.write_controlword(0x80);
    assert_eq!(device.state(), State::Fault);
    device.write_controlword(0x00);
    assert_eq!(device.write_controlword(0x80).map(|t| t.name), Some("15"));
    assert_eq!(device.state(), State::SwitchOnDisabled);
}
