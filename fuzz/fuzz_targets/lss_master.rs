//! The LSS (CiA 305) master fed arbitrary frames on 7E4h (what slaves, or a broken or hostile
//! node, send it): the answer decoder, one exchange per kind of command and a Fastscan.
//!
//! Input: chunks of one control byte (low nibble: length, 0-8; bit 4: the frame's id is 7E4h,
//! else 7E5h; bits 5-7: milliseconds to advance the clock) and up to 8 data bytes. Never panics;
//! asserts that a decoded answer re-encodes to a frame that decodes to it, that a command only
//! one slave may answer never ends done with two answers, that nothing ends before its deadline
//! without an answer, and that a Fastscan sends at most its 133 steps.
#![no_main]

use core::time::Duration;

use drivebus::canopen::lss::{
    Answers, Command, Exchange, Fastscan, FastscanProgress, IdentityWord, LssMode, NewNodeId,
    Progress, Response, MASTER_COB, SLAVE_COB,
};
use drivebus::canopen::CanFrame;
use libfuzzer_sys::fuzz_target;

/// The frames of the input, each with the time it arrives.
fn frames(mut input: &[u8]) -> Vec<(CanFrame, Duration)> {
    let mut out = Vec::new();
    let mut now = Duration::ZERO;
    while let Some((&control, rest)) = input.split_first() {
        let len = usize::from(control & 0x0F).min(8).min(rest.len());
        let id = if control & 0x10 != 0 { SLAVE_COB } else { MASTER_COB };
        now += Duration::from_millis(u64::from(control >> 5));
        out.push((CanFrame::new(id, &rest[..len]).unwrap(), now));
        input = &rest[len..];
    }
    out
}

fn commands() -> [Command; 6] {
    [
        Command::SwitchSelective(IdentityWord::Serial, 1),
        Command::ConfigureNodeId(NewNodeId::Unconfigured),
        Command::Store,
        Command::InquireNodeId,
        Command::IdentifyNonConfigured,
        Command::SwitchGlobal(LssMode::Waiting),
    ]
}

fn exchange(command: Command, frames: &[(CanFrame, Duration)]) {
    let timeout = Duration::from_millis(20);
    let mut exchange = Exchange::single(command, timeout, Duration::ZERO);
    while exchange.poll_transmit().is_some() {}
    for (frame, now) in frames {
        let progress = match exchange.handle_timeout(*now) {
            Progress::Pending => exchange.handle(frame, *now),
            ended => ended,
        };
        match progress {
            Progress::Done(outcome) => {
                if exchange.answers() == Answers::One && command.expects_answer() {
                    assert_eq!(outcome.count, 1, "{command:?}");
                    assert!(command.is_answered_by(&outcome.response.unwrap()));
                }
            }
            Progress::Failed(_) => {}
            Progress::Pending => assert!(exchange.deadline().is_some_and(|d| *now < d)),
        }
    }
}

fn fastscan(frames: &[(CanFrame, Duration)]) {
    let mut scan = Fastscan::new(Duration::from_millis(1), Duration::ZERO);
    let mut sent = 0;
    for (frame, now) in frames {
        while scan.poll_transmit().is_some() {
            sent += 1;
        }
        scan.handle(frame, *now);
        if let FastscanProgress::Found(_) | FastscanProgress::NoneLeft | FastscanProgress::Failed(_) =
            scan.handle_timeout(*now)
        {
            assert!(scan.deadline().is_none());
        }
    }
    assert!(sent <= 133, "{sent} Fastscan steps");
}

fuzz_target!(|input: &[u8]| {
    let frames = frames(input);
    for (frame, _) in &frames {
        if let Some(response) = Response::decode(frame) {
            assert_eq!(Response::decode(&response.encode()), Some(response));
        }
        if let Some(command) = Command::decode(frame) {
            assert_eq!(Command::decode(&command.encode()), Some(command));
        }
    }
    for command in commands() {
        exchange(command, &frames);
    }
    fastscan(&frames);
});
