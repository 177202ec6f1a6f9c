//! The PDO traffic of one CAN bus the gateway serves: one SYNC stream for the whole bus (every
//! `interval_ms` of its fastest drive with `pdo = true`; none when no drive takes its TPDO at
//! SYNC), and the newest TPDO on each CAN identifier, kept until a drive's poll takes it. The
//! bus's poller owns it: SYNCs go out between polls, the other drives' SDO polls and the
//! writes go on between SYNCs, and the TPDOs that came meanwhile (kept by the SDO client) are
//! taken at the next look.

use std::collections::BTreeMap;
use std::time::{Duration, Instant};

use drivebus::canopen::frame::cob;
use drivebus::canopen::{CanBus, CanFrame};
use drivegen::gateway_file::PdoUse;

use super::exposed::Drive;
use crate::connect::{hold, SharedCan};
use crate::error::CliError;

/// Longest single wait on the bus while a poll waits for its TPDO: a SYNC due meanwhile goes
/// out at most this late.
const NAP: Duration = Duration::from_millis(5);

/// A TPDO as it came.
struct Received {
    payload: Vec<u8>,
    /// When it came.
    at: Instant,
    /// Its place among every TPDO the bus took (a drive takes each one once).
    seq: u64,
}

/// A CAN bus's SYNC schedule and the TPDOs that came on it.
pub struct PdoBus {
    /// Between SYNCs; `None`: no drive takes its TPDO at SYNC.
    period: Option<Duration>,
    /// When the next SYNC is due.
    next_sync: Instant,
    /// When the last SYNC went out.
    last_sync: Option<Instant>,
    /// The newest TPDO on each CAN identifier.
    inbox: BTreeMap<u16, Received>,
    /// How many frames were taken in.
    seq: u64,
}

impl PdoBus {
    /// The PDO traffic of a bus whose drives are `drives`; `None` when none takes PDOs. The
    /// SYNC period is the smallest `interval_ms` among the drives at SYNC: each then has a
    /// TPDO at least as new as its own interval at every poll.
    pub fn new<'a>(drives: impl IntoIterator<Item = &'a Drive>) -> Option<Self> {
        let mut by_pdo = false;
        let mut period: Option<u32> = None;
        for drive in drives {
            by_pdo |= drive.pdo.on();
            if drive.pdo == PdoUse::Sync {
                period = Some(period.map_or(drive.interval_ms, |p| p.min(drive.interval_ms)));
            }
        }
        by_pdo.then(|| Self::with_period(period.map(|ms| Duration::from_millis(ms.into()))))
    }

    /// A SYNC every `period` (`None`: no SYNC), the first one due now.
    fn with_period(period: Option<Duration>) -> Self {
        Self {
            period,
            next_sync: Instant::now(),
            last_sync: None,
            inbox: BTreeMap::new(),
            seq: 0,
        }
    }

    /// When the next SYNC is due, if the bus has a SYNC stream.
    pub fn next_sync(&self) -> Option<Instant> {
        self.period.map(|_| self.next_sync)
    }

    /// The SYNC due now, if any, on `bus` (`None`: the bus is not open, the SYNC is skipped),
    /// the TPDOs that came before it taken in first: what comes after answers it.
    pub fn tick(&mut self, bus: Option<&SharedCan>) -> Result<(), CliError> {
        let Some(period) = self.period else {
            return Ok(());
        };
        let now = Instant::now();
        if now < self.next_sync {
            return Ok(());
        }
        // On schedule, as `watch --pdo`: a SYNC sent late does not move the next ones; after
        // a stall (a silent drive's timeout) the schedule starts again from now, no burst.
        self.next_sync += period;
        if self.next_sync < now {
            self.next_sync = now + period;
        }
        match bus {
            Some(bus) => {
                self.take_in(bus, Duration::ZERO, None)?;
                self.sync(bus).map(|_| ())
            }
            None => Ok(()),
        }
    }

    /// Sends a SYNC now.
    fn sync(&mut self, bus: &SharedCan) -> Result<Instant, CliError> {
        let sync = CanFrame::new(cob::SYNC, &[]).map_err(|e| CliError::Io(e.to_string()))?;
        hold(bus)
            .send(&sync)
            .map_err(|e| CliError::Io(format!("SYNC: {e}")))?;
        let now = Instant::now();
        self.last_sync = Some(now);
        Ok(now)
    }

    /// When the last SYNC went out; one sent now if none went out yet (the bus was not open
    /// until this poll).
    pub fn last_sync(&mut self, bus: &SharedCan) -> Result<Instant, CliError> {
        match self.last_sync {
            Some(at) => Ok(at),
            None => self.sync(bus),
        }
    }

    /// Takes in the frames waiting on `bus`; the number of the last one, so that only those
    /// that come after are taken (a TPDO begun now).
    pub fn mark(&mut self, bus: &SharedCan) -> Result<u64, CliError> {
        self.take_in(bus, Duration::ZERO, None)?;
        Ok(self.seq)
    }

    /// The newest TPDO on `can_id` that came after the one numbered `taken` and not before
    /// `since`, waiting for it until `deadline` (SYNCs going out on schedule meanwhile), with
    /// its number; `None` when none came.
    pub fn take(
        &mut self,
        bus: &SharedCan,
        can_id: u16,
        taken: u64,
        since: Option<Instant>,
        deadline: Instant,
    ) -> Result<Option<(Vec<u8>, u64)>, CliError> {
        let fresh = |r: &Received| r.seq > taken && since.is_none_or(|s| r.at >= s);
        loop {
            self.take_in(bus, Duration::ZERO, None)?;
            if let Some(got) = self.inbox.get(&can_id).filter(|r| fresh(r)) {
                return Ok(Some((got.payload.clone(), got.seq)));
            }
            let now = Instant::now();
            if now >= deadline {
                return Ok(None);
            }
            self.tick(Some(bus))?;
            let mut wake = deadline.min(now + NAP);
            if let Some(next) = self.next_sync() {
                wake = wake.min(next);
            }
            self.take_in(bus, wake.saturating_duration_since(now), Some(can_id))?;
        }
    }

    /// Takes in the frames on the bus: every one waiting, then, while `wait` lasts, those that
    /// come, until one on `until` came.
    fn take_in(
        &mut self,
        bus: &SharedCan,
        wait: Duration,
        until: Option<u16>,
    ) -> Result<(), CliError> {
        let deadline = Instant::now() + wait;
        let mut held = hold(bus);
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            let frame = held
                .recv(left)
                .map_err(|e| CliError::Io(format!("CAN bus: {e}")))?;
            let Some(frame) = frame else {
                return Ok(());
            };
            if frame.is_remote() {
                continue;
            }
            self.seq += 1;
            let received = Received {
                payload: frame.data().to_vec(),
                at: Instant::now(),
                seq: self.seq,
            };
            self.inbox.insert(frame.id(), received);
            if until == Some(frame.id()) {
                return Ok(());
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use std::collections::VecDeque;
    use std::sync::{Arc, Mutex};

    use drivebus::canopen::client::BlockingSdo;
    use drivebus::BusError;

    use super::*;
    use crate::connect::DynCan;

    type Frames = Arc<Mutex<VecDeque<CanFrame>>>;

    /// A bus that hands out `incoming` and keeps what is sent in `sent`.
    struct Fake {
        incoming: Frames,
        sent: Frames,
    }

    impl CanBus for Fake {
        fn send(&mut self, frame: &CanFrame) -> Result<(), BusError> {
            self.sent.lock().unwrap().push_back(*frame);
            Ok(())
        }
        fn recv(&mut self, timeout: Duration) -> Result<Option<CanFrame>, BusError> {
            let frame = self.incoming.lock().unwrap().pop_front();
            if frame.is_none() {
                std::thread::sleep(timeout.min(Duration::from_millis(1)));
            }
            Ok(frame)
        }
    }

    fn bus() -> (SharedCan, Frames, Frames) {
        let (incoming, sent) = (Frames::default(), Frames::default());
        let fake = Fake {
            incoming: Arc::clone(&incoming),
            sent: Arc::clone(&sent),
        };
        let shared = Arc::new(Mutex::new(BlockingSdo::new(DynCan(Box::new(fake)))));
        (shared, incoming, sent)
    }

    fn frame(id: u16, data: &[u8]) -> CanFrame {
        CanFrame::new(id, data).unwrap()
    }

    fn syncs(sent: &Frames) -> usize {
        let sent = sent.lock().unwrap();
        sent.iter().filter(|f| f.id() == cob::SYNC).count()
    }

    #[test]
    fn each_tpdo_is_taken_once_and_a_late_one_is_none() {
        let (shared, incoming, _) = bus();
        let mut pdo = PdoBus::with_period(None);
        incoming
            .lock()
            .unwrap()
            .extend([frame(0x190, &[1]), frame(0x290, &[2])]);
        let soon = || Instant::now() + Duration::from_millis(20);
        let (payload, seq) = pdo.take(&shared, 0x290, 0, None, soon()).unwrap().unwrap();
        assert_eq!(payload, [2]);
        let (other, _) = pdo.take(&shared, 0x190, 0, None, soon()).unwrap().unwrap();
        assert_eq!(other, [1], "kept while another drive's TPDO was waited for");
        assert_eq!(pdo.take(&shared, 0x290, seq, None, soon()).unwrap(), None);
        incoming.lock().unwrap().push_back(frame(0x290, &[3]));
        let (newer, _) = pdo
            .take(&shared, 0x290, seq, None, soon())
            .unwrap()
            .unwrap();
        assert_eq!(newer, [3]);
    }

    #[test]
    fn syncs_go_out_on_schedule_and_only_with_a_period() {
        let (shared, incoming, sent) = bus();
        let mut none = PdoBus::with_period(None);
        assert_eq!(none.next_sync(), None);
        none.tick(Some(&shared)).unwrap();
        assert_eq!(syncs(&sent), 0, "no drive at SYNC: no SYNC");

        let period = Duration::from_millis(50);
        let mut pdo = PdoBus::with_period(Some(period));
        pdo.tick(None).unwrap();
        assert_eq!(syncs(&sent), 0, "the bus not open: skipped");
        let since = pdo.last_sync(&shared).unwrap();
        assert_eq!(syncs(&sent), 1, "the first poll sends one");
        pdo.tick(Some(&shared)).unwrap();
        assert_eq!(syncs(&sent), 1, "not due yet");
        // Waiting for a TPDO that comes late: SYNCs keep going out meanwhile.
        let deadline = Instant::now() + 5 * period;
        assert_eq!(
            pdo.take(&shared, 0x190, 0, Some(since), deadline).unwrap(),
            None
        );
        assert!((3..=6).contains(&syncs(&sent)), "{}", syncs(&sent));
        incoming.lock().unwrap().push_back(frame(0x190, &[7]));
        let later = pdo.last_sync(&shared).unwrap();
        assert!(later > since);
        let got = pdo
            .take(&shared, 0x190, 0, Some(later), deadline + period)
            .unwrap();
        assert_eq!(got.map(|g| g.0), Some(vec![7]));
    }
}
