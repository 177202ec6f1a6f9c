//! The blocking master against LSS slaves on a simulated bus: the bad input of issue 34.

use std::collections::VecDeque;
use std::vec;
use std::vec::Vec;

use super::*;
use crate::canopen::frame::CanFrame;
use crate::canopen::lss::{ConfigureError, LssSlave, MASTER_COB};
use crate::error::BusError;

/// A bus where every sent frame reaches every slave, whose answers come back in order.
struct Slaves {
    slaves: Vec<LssSlave>,
    inbound: VecDeque<CanFrame>,
    sent: Vec<CanFrame>,
}

impl Slaves {
    fn new(slaves: Vec<LssSlave>) -> Self {
        Self {
            slaves,
            inbound: VecDeque::new(),
            sent: Vec::new(),
        }
    }
}

impl CanBus for Slaves {
    fn send(&mut self, frame: &CanFrame) -> Result<(), BusError> {
        self.sent.push(*frame);
        for slave in &mut self.slaves {
            self.inbound.extend(slave.handle(frame).0);
        }
        Ok(())
    }
    fn recv(&mut self, timeout: Duration) -> Result<Option<CanFrame>, BusError> {
        let frame = self.inbound.pop_front();
        if frame.is_none() {
            std::thread::sleep(timeout);
        }
        Ok(frame)
    }
}

fn address(serial: u32) -> LssAddress {
    LssAddress {
        vendor_id: 0x0000_02E1,
        product_code: 0x0000_0100,
        revision: 0x0001_0000,
        serial,
    }
}

fn master(slaves: Vec<LssSlave>) -> BlockingLss<Slaves> {
    BlockingLss::new(Slaves::new(slaves))
        .with_timeout(Duration::from_millis(30))
        .with_fastscan_step(Duration::from_millis(2))
}

fn slave(serial: u32, node: u8) -> LssSlave {
    LssSlave::new(address(serial), node, BitTiming::K1000)
}

#[test]
fn a_selective_switch_nobody_answers_is_no_answer() {
    let mut lss = master(vec![slave(1, 10)]);
    assert_eq!(lss.switch_selective(address(2)), Err(LssError::NoAnswer));
    assert_eq!(
        lss.bus_mut().sent.len(),
        4,
        "vendor, product, revision, serial"
    );
}

#[test]
fn two_nodes_answering_one_selective_switch_is_an_error() {
    let mut lss = master(vec![slave(7, 10), slave(7, 11)]);
    assert_eq!(
        lss.switch_selective(address(7)),
        Err(LssError::SeveralAnswers)
    );
}

#[test]
fn invalid_node_ids_are_refused_before_anything_is_sent() {
    let mut lss = master(vec![slave(1, 10)]);
    lss.switch_selective(address(1)).unwrap();
    let before = lss.bus_mut().sent.len();
    for raw in [0u8, 128, 254] {
        assert_eq!(
            lss.configure_node_id(raw),
            Err(LssError::InvalidNodeId(raw))
        );
    }
    assert_eq!(lss.bus_mut().sent.len(), before, "nothing sent");
    assert_eq!(lss.configure_node_id(127), Ok(()));
}

#[test]
fn a_refused_bit_rate_carries_the_slaves_error_code() {
    let only_fast = slave(1, 10).with_bit_timings(&[BitTiming::K1000, BitTiming::K500]);
    let mut lss = master(vec![only_fast]);
    lss.switch_selective(address(1)).unwrap();
    assert_eq!(
        lss.configure_bit_timing(BitTiming::K125),
        Err(LssError::Refused(ConfigureError::BitTimingNotSupported))
    );
    assert_eq!(lss.configure_bit_timing(BitTiming::K500), Ok(()));
    let unstorable = slave(2, 11).with_store(false);
    let mut lss = master(vec![unstorable]);
    lss.switch_selective(address(2)).unwrap();
    assert_eq!(
        lss.store(),
        Err(LssError::Refused(ConfigureError::StoreNotSupported))
    );
}

#[test]
fn nothing_is_stored_unless_asked() {
    let mut lss = master(vec![slave(1, 10)]);
    lss.switch_selective(address(1)).unwrap();
    lss.configure_node_id(5).unwrap();
    lss.configure_bit_timing(BitTiming::K250).unwrap();
    lss.switch_global(LssMode::Waiting).unwrap();
    let sent = &lss.bus_mut().sent;
    assert!(
        sent.iter()
            .all(|f| f.id() == MASTER_COB && f.data()[0] != 0x17),
        "no store sent"
    );
    let node = &mut lss.bus_mut().slaves[0];
    assert_eq!(node.pending_node_id(), 5);
    assert_eq!(
        node.power_cycle(),
        10,
        "a power cycle forgets what was not stored"
    );
    assert_eq!(node.bit_timing(), BitTiming::K1000);
}

#[test]
fn a_stored_node_id_survives_a_power_cycle() {
    let mut lss = master(vec![slave(1, 10)]);
    lss.switch_selective(address(1)).unwrap();
    assert_eq!(lss.inquire_node_id(), Ok(10));
    assert_eq!(lss.inquire_address(), Ok(address(1)));
    lss.configure_node_id(5).unwrap();
    lss.store().unwrap();
    lss.switch_global(LssMode::Waiting).unwrap();
    assert_eq!(lss.bus_mut().slaves[0].power_cycle(), 5);
}

#[test]
fn fastscan_finds_each_non_configured_node_in_turn_and_then_none() {
    let mut lss = master(vec![
        slave(0x0000_0B02, 0xFF),
        slave(0x0000_0A01, 0xFF),
        slave(3, 12),
    ]);
    assert_eq!(lss.identify_non_configured(), Ok(2));
    let mut given = Vec::new();
    for id in [20u8, 21] {
        let found = lss.fastscan().unwrap().expect("a non-configured node");
        lss.configure_node_id(id).unwrap();
        lss.switch_global(LssMode::Waiting).unwrap();
        given.push((found.serial, id));
    }
    assert_eq!(
        given,
        [(0x0A01, 20), (0x0B02, 21)],
        "smallest address first"
    );
    assert_eq!(lss.fastscan(), Ok(None));
    let ids: Vec<u8> = lss.bus_mut().slaves.iter().map(LssSlave::node_id).collect();
    assert_eq!(
        ids,
        [21, 20, 12],
        "each took its id when switched back to waiting"
    );
    assert_eq!(
        lss.identify_remote(0x02E1, 0x0100, 0..=u32::MAX, 0..=0x0A01),
        Ok(2)
    );
}

/// A bus that never stops delivering heartbeats and never answers LSS.
struct Chatter;

impl CanBus for Chatter {
    fn send(&mut self, _: &CanFrame) -> Result<(), BusError> {
        Ok(())
    }
    fn recv(&mut self, _: Duration) -> Result<Option<CanFrame>, BusError> {
        Ok(Some(CanFrame::new(0x705, &[0x05]).unwrap()))
    }
}

#[test]
fn other_traffic_does_not_hold_a_command_past_its_timeout() {
    let mut lss = BlockingLss::new(Chatter).with_timeout(Duration::from_millis(20));
    let started = std::time::Instant::now();
    assert_eq!(lss.inquire_node_id(), Err(LssError::NoAnswer));
    assert_eq!(lss.identify_non_configured(), Ok(0));
    assert_eq!(lss.fastscan(), Ok(None));
    assert!(started.elapsed() < Duration::from_secs(2));
}
