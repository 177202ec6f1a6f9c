//! The async master against LSS slaves on a simulated bus, polled without an executor: the
//! bus answers at once or never, the timer's every sleep is over at once, so each operation
//! completes in one poll.

use std::collections::VecDeque;
use std::vec;
use std::vec::Vec;

use super::*;
use crate::canopen::lss::{BitTiming, ConfigureError, LssMode, LssSlave};
use crate::testing::now;

/// A bus where every sent frame reaches every slave, whose answers come back in order, after
/// `foreign` frames of other traffic.
struct Slaves {
    slaves: Vec<LssSlave>,
    inbound: VecDeque<CanFrame>,
    foreign: usize,
}

impl AsyncCanBus for Slaves {
    async fn send(&mut self, frame: &CanFrame) -> Result<(), BusError> {
        for slave in &mut self.slaves {
            self.inbound.extend(slave.handle(frame).0);
        }
        Ok(())
    }

    async fn recv(&mut self) -> Result<CanFrame, BusError> {
        if self.foreign > 0 {
            self.foreign -= 1;
            return Ok(CanFrame::new(0x701, &[0x05]).expect("a heartbeat"));
        }
        match self.inbound.pop_front() {
            Some(frame) => Ok(frame),
            None => core::future::pending().await,
        }
    }
}

/// Every sleep is over at once: a step's time has passed as soon as the bus is quiet.
struct NoWait;

impl Timer for NoWait {
    type Alarm = NoWait;

    fn alarm(&self) -> NoWait {
        NoWait
    }

    async fn sleep(&self, _: Duration) {}
}

impl crate::asynch::Alarm for NoWait {
    fn set(&mut self, _: Duration) {}

    fn poll_due(&mut self, _: &mut core::task::Context<'_>) -> core::task::Poll<()> {
        core::task::Poll::Ready(())
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

fn master(slaves: Vec<LssSlave>, foreign: usize) -> AsyncLss<Slaves, NoWait> {
    let bus = Slaves {
        slaves,
        inbound: VecDeque::new(),
        foreign,
    };
    AsyncLss::new(bus, NoWait)
}

fn slave(serial: u32, node: u8) -> LssSlave {
    LssSlave::new(address(serial), node, BitTiming::K1000)
}

#[test]
fn configure_inquire_and_store_through_the_shared_requests() {
    let mut lss = master(vec![slave(1, 10)], 3);
    let done = now(async {
        lss.request(request::switch_selective(address(1))).await?;
        assert_eq!(lss.request(request::inquire_node_id()).await?, 10);
        assert_eq!(lss.inquire_address().await?, address(1));
        lss.request(request::configure_node_id(5)?).await?;
        lss.request(request::store()).await?;
        lss.request(request::switch_global(LssMode::Waiting)).await
    });
    assert_eq!(done, Some(Ok(())));
    assert_eq!(lss.bus_mut().slaves[0].power_cycle(), 5, "stored");
}

#[test]
fn bad_input_gets_the_typed_errors_of_the_blocking_master() {
    let mut lss = master(vec![slave(7, 10), slave(7, 11)], 0);
    let several = now(lss.request(request::switch_selective(address(7))));
    assert_eq!(several, Some(Err(LssError::SeveralAnswers)));
    let nobody = now(lss.request(request::switch_selective(address(8))));
    assert_eq!(nobody, Some(Err(LssError::NoAnswer)));
    assert_eq!(
        request::configure_node_id(0).err(),
        Some(LssError::InvalidNodeId(0))
    );
    let only_fast = slave(1, 10).with_bit_timings(&[BitTiming::K1000]);
    let mut lss = master(vec![only_fast], 0);
    let refused = now(async {
        lss.request(request::switch_selective(address(1))).await?;
        lss.request(request::configure_bit_timing(BitTiming::K125))
            .await
    });
    assert_eq!(
        refused,
        Some(Err(LssError::Refused(
            ConfigureError::BitTimingNotSupported
        )))
    );
}

#[test]
fn fastscan_finds_each_non_configured_node_in_turn_and_then_none() {
    let mut lss = master(
        vec![slave(0x0B02, 0xFF), slave(0x0A01, 0xFF), slave(3, 12)],
        5,
    );
    let given = now(async {
        let mut given = Vec::new();
        for id in [20u8, 21] {
            let found = lss.fastscan().await?.expect("a non-configured node");
            lss.request(request::configure_node_id(id)?).await?;
            lss.request(request::switch_global(LssMode::Waiting))
                .await?;
            given.push((found.serial, id));
        }
        assert_eq!(lss.fastscan().await?, None);
        Ok::<_, LssError>(given)
    });
    assert_eq!(given, Some(Ok(vec![(0x0A01, 20), (0x0B02, 21)])));
    let ids: Vec<u8> = lss.bus_mut().slaves.iter().map(LssSlave::node_id).collect();
    assert_eq!(ids, [21, 20, 12]);
}
