//! Exhaustive tests of the CiA 402 planner: every state × target, every quirk, and a simulated
//! drive walked from every state to every target.

use super::*;
use crate::control::device::Cia402Device;
use crate::control::quirks::Quirk;

/// The statusword a CiA 402 device shows in `state`, remote (bit 9) set where it is processing
/// the controlword (the device side's values for a drive that honours remote).
fn statusword(state: State) -> u16 {
    let remote = Quirks::STANDARD.with(Quirk::HonoursRemote);
    Cia402Device::in_state(state)
        .with_quirks(remote)
        .statusword()
}

fn seen(state: State) -> Observation {
    Observation {
        statusword: statusword(state),
        safe_torque_off: false,
        now: Millis(0),
    }
}

/// A planner that last wrote a controlword with bit 7 low.
fn planner(quirks: Quirks) -> Cia402Planner {
    let mut planner = Cia402Planner::new(quirks);
    planner.sent(command::SHUTDOWN, Millis(0));
    planner
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Expect {
    Done,
    Send(u16, &'static str),
    Auto(&'static str),
    Blocked(Blocker),
}

fn outcome(step: Step) -> Expect {
    match step {
        Step::Done => Expect::Done,
        Step::Send {
            controlword,
            transition,
        } => Expect::Send(controlword, transition.name),
        Step::Wait(Waiting::Automatic(t)) => Expect::Auto(t.name),
        Step::Wait(other) => panic!("unexpected wait {other:?}"),
        Step::Blocked(blocker) => Expect::Blocked(blocker),
    }
}

#[test]
fn every_statusword_decodes_to_at_most_one_state_and_the_canonical_ones_to_theirs() {
    for state in State::ALL {
        assert_eq!(State::decode(statusword(state)), Some(state));
        assert_eq!(State::ALL[usize::from(state.index())], state);
    }
    for word in 0..=u16::MAX {
        let matching = TABLE
            .states
            .iter()
            .filter(|s| s.patterns.iter().any(|p| p.matches(word)))
            .count();
        assert!(matching <= 1, "{word:#06x} matches {matching} states");
    }
    assert_eq!(State::decode(0x0001), None);
    assert_eq!(
        State::decode(0x0050),
        Some(State::SwitchOnDisabled),
        "bit 4 does not decide"
    );
}

#[test]
fn every_state_and_target_has_the_standard_next_step() {
    use Expect::{Auto, Blocked as B, Done, Send};
    let only_from_oe = B(Blocker::QuickStopOnlyFromOperationEnabled);
    // Columns: switch on disabled, ready to switch on, switched on, operation enabled, quick stop.
    let table: [(State, [Expect; 5]); 8] = [
        (
            State::NotReadyToSwitchOn,
            [Auto("1"), Auto("1"), Auto("1"), Auto("1"), Auto("1")],
        ),
        (
            State::SwitchOnDisabled,
            [
                Done,
                Send(0x06, "2"),
                Send(0x06, "2"),
                Send(0x06, "2"),
                only_from_oe,
            ],
        ),
        (
            State::ReadyToSwitchOn,
            [
                Send(0x00, "7"),
                Done,
                Send(0x07, "3"),
                Send(0x07, "3"),
                only_from_oe,
            ],
        ),
        (
            State::SwitchedOn,
            [
                Send(0x00, "10"),
                Send(0x06, "6"),
                Done,
                Send(0x0F, "4"),
                only_from_oe,
            ],
        ),
        (
            State::OperationEnabled,
            [
                Send(0x00, "9"),
                Send(0x06, "8"),
                Send(0x07, "5"),
                Done,
                Send(0x02, "11"),
            ],
        ),
        (
            State::QuickStopActive,
            [
                Send(0x00, "12"),
                Send(0x00, "12"),
                Send(0x00, "12"),
                Send(0x00, "12"),
                Done,
            ],
        ),
        (
            State::FaultReactionActive,
            [Auto("14"), Auto("14"), Auto("14"), Auto("14"), Auto("14")],
        ),
        (
            State::Fault,
            [
                Send(0x80, "15"),
                Send(0x80, "15"),
                Send(0x80, "15"),
                Send(0x80, "15"),
                Send(0x80, "15"),
            ],
        ),
    ];
    let planner = planner(Quirks::STANDARD);
    for (state, row) in table {
        for (target, expected) in Target::ALL.into_iter().zip(row) {
            let got = outcome(planner.next(&seen(state), target));
            assert_eq!(got, expected, "{state:?} → {target:?}");
        }
    }
}

#[test]
fn every_commanded_transition_of_the_table_is_planned_somewhere() {
    let quirks = Quirks::STANDARD.with(Quirk::QuickStopToOperationEnabled);
    let planner = planner(quirks);
    let mut planned = std::vec::Vec::new();
    for state in State::ALL {
        for target in Target::ALL {
            if let Step::Send { transition, .. } = planner.next(&seen(state), target) {
                planned.push(transition.name);
            }
        }
    }
    for t in TABLE
        .transitions
        .iter()
        .filter(|t| matches!(t.kind, TransitionKind::Command(_)))
    {
        assert!(
            planned.contains(&t.name),
            "transition {} is never planned",
            t.name
        );
    }
}

#[test]
fn unknown_statuswords_block_with_the_word() {
    let step = planner(Quirks::STANDARD).next(
        &Observation {
            statusword: 0x0001,
            safe_torque_off: false,
            now: Millis(0),
        },
        Target::OperationEnabled,
    );
    assert_eq!(step, Step::Blocked(Blocker::UnknownStatusword(0x0001)));
}

#[test]
fn halt_is_carried_in_every_command() {
    let mut planner = planner(Quirks::STANDARD);
    planner.set_halt(true);
    let step = planner.next(&seen(State::SwitchedOn), Target::OperationEnabled);
    assert!(
        matches!(
            step,
            Step::Send {
                controlword: 0x010F,
                ..
            }
        ),
        "{step:?}"
    );
}

#[test]
fn fault_reset_is_a_rising_edge_even_when_bit_7_was_left_high() {
    let mut planner = Cia402Planner::new(Quirks::STANDARD);
    planner.sent(command::FAULT_RESET, Millis(0));
    let fault = seen(State::Fault);
    assert!(matches!(
        planner.next(&fault, Target::OperationEnabled),
        Step::Send {
            controlword: 0x00,
            ..
        }
    ));
    planner.sent(0x00, Millis(1));
    assert!(matches!(
        planner.next(&fault, Target::OperationEnabled),
        Step::Send {
            controlword: 0x80,
            ..
        }
    ));
}

#[test]
fn fault_reset_from_an_unknown_controlword_drops_bit_7_first() {
    let planner = Cia402Planner::new(Quirks::STANDARD);
    assert!(matches!(
        planner.next(&seen(State::Fault), Target::SwitchOnDisabled),
        Step::Send {
            controlword: 0x00,
            ..
        }
    ));
}

#[test]
fn quirk_fault_reset_hold_keeps_bit_7_high_for_the_minimum_time() {
    let mut planner = planner(Quirks {
        fault_reset_hold_ms: 50,
        ..Quirks::STANDARD
    });
    let at = |ms| Observation {
        now: Millis(ms),
        ..seen(State::Fault)
    };
    assert!(matches!(
        planner.next(&at(0), Target::SwitchOnDisabled),
        Step::Send {
            controlword: 0x80,
            ..
        }
    ));
    planner.sent(0x80, Millis(100));
    assert_eq!(
        planner.next(&at(130), Target::SwitchOnDisabled),
        Step::Wait(Waiting::FaultResetHold { remaining_ms: 20 })
    );
    assert!(matches!(
        planner.next(&at(150), Target::SwitchOnDisabled),
        Step::Send {
            controlword: 0x00,
            ..
        }
    ));
}

#[test]
fn quirk_quick_stop_to_operation_enabled_uses_transition_16() {
    let planner = planner(Quirks::STANDARD.with(Quirk::QuickStopToOperationEnabled));
    let step = outcome(planner.next(&seen(State::QuickStopActive), Target::OperationEnabled));
    assert_eq!(step, Expect::Send(0x0F, "16"));
}

#[test]
fn quirk_switch_on_needs_voltage_waits_for_bit_4() {
    let planner = planner(Quirks::STANDARD.with(Quirk::SwitchOnNeedsVoltage));
    let no_voltage = Observation {
        statusword: 0x0221,
        ..seen(State::ReadyToSwitchOn)
    };
    let step = planner.next(&no_voltage, Target::OperationEnabled);
    assert_eq!(step, Step::Blocked(Blocker::VoltageNotEnabled));
    assert!(
        !Blocker::VoltageNotEnabled.is_final(),
        "voltage may still come"
    );
    let voltage = Observation {
        statusword: 0x0231,
        ..seen(State::ReadyToSwitchOn)
    };
    let with_voltage = outcome(planner.next(&voltage, Target::OperationEnabled));
    assert_eq!(with_voltage, Expect::Send(0x07, "3"));
    let standard =
        outcome(self::planner(Quirks::STANDARD).next(&no_voltage, Target::OperationEnabled));
    assert_eq!(standard, Expect::Send(0x07, "3"));
}

#[test]
fn quirk_honours_remote_waits_while_bit_9_is_clear() {
    let local = Observation {
        statusword: 0x0040,
        ..seen(State::SwitchOnDisabled)
    };
    let quirky = planner(Quirks::STANDARD.with(Quirk::HonoursRemote));
    assert_eq!(
        quirky.next(&local, Target::OperationEnabled),
        Step::Blocked(Blocker::NotRemote)
    );
    let remote = outcome(quirky.next(&seen(State::SwitchOnDisabled), Target::OperationEnabled));
    assert_eq!(remote, Expect::Send(0x06, "2"));
    let standard = outcome(planner(Quirks::STANDARD).next(&local, Target::OperationEnabled));
    assert_eq!(standard, Expect::Send(0x06, "2"));
}

#[test]
fn safe_torque_off_keeps_the_drive_disabled_and_says_so() {
    let planner = planner(Quirks::STANDARD);
    let sto = Observation {
        safe_torque_off: true,
        ..seen(State::SwitchOnDisabled)
    };
    for target in [
        Target::ReadyToSwitchOn,
        Target::SwitchedOn,
        Target::OperationEnabled,
    ] {
        assert_eq!(
            planner.next(&sto, target),
            Step::Blocked(Blocker::SafeTorqueOff)
        );
    }
    assert!(Blocker::SafeTorqueOff.is_final());
    assert_eq!(planner.next(&sto, Target::SwitchOnDisabled), Step::Done);
    let enabled = Observation {
        safe_torque_off: true,
        ..seen(State::OperationEnabled)
    };
    assert_eq!(
        outcome(planner.next(&enabled, Target::SwitchOnDisabled)),
        Expect::Send(0x00, "9")
    );
}

#[test]
fn a_simulated_drive_reaches_every_target_from_every_state() {
    for start in State::ALL {
        for target in Target::ALL {
            let mut drive = Cia402Device::in_state(start).with_controlword(0x80);
            let mut planner = Cia402Planner::new(Quirks::STANDARD);
            planner.sent(drive.controlword(), Millis(0));
            let mut steps = 0;
            loop {
                steps += 1;
                assert!(steps < 20, "{start:?} → {target:?} does not converge");
                match planner.next(&seen(drive.state()), target) {
                    Step::Done => break,
                    Step::Send { controlword, .. } => {
                        drive.write_controlword(controlword);
                        planner.sent(controlword, Millis(steps));
                    }
                    Step::Wait(_) => {
                        drive.tick();
                    }
                    Step::Blocked(Blocker::QuickStopOnlyFromOperationEnabled) => {
                        assert_eq!(target, Target::QuickStopActive);
                        break;
                    }
                    Step::Blocked(other) => panic!("{start:?} → {target:?}: {other:?}"),
                }
            }
        }
    }
}
