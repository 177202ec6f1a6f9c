//! What a cyclic shell decides, without I/O: the axis planners made from the drives' answers
//! (6502h, 6065h), the SDO writes that set the mode and the interpolation period, what a
//! subscriber's event means for an axis, and each cycle once every axis's feedback came (the
//! enable time limit, the cycle timing, the RPDO of each axis). The blocking shell
//! (`cyclic_driver`) and the async one (`async_cyclic_driver`) both run these, so they differ
//! only in how they read, write and wait.

use core::time::Duration;
use std::time::Instant;
use std::vec::Vec;

use super::cycle_stats::CycleStats;
use super::cyclic::{Command, CyclicAxis, Feedback};
use super::cyclic_driver::{AxisLink, CyclicConfig, CyclicError};
use super::position::operation_enabled;
use super::Millis;
use crate::canopen::emcy::Emcy;
#[cfg(feature = "async")]
use crate::canopen::network::{AsyncNetwork, AsyncSubscription};
use crate::canopen::network::{Network, NetworkEvent, Subscription};
use crate::canopen::{CanFrame, NodeId};
use crate::error::BusError;

/// One axis of a run: its link, planner, last feedback and last emergency.
#[derive(Debug)]
pub(crate) struct Axis {
    pub(crate) link: AxisLink,
    pub(crate) planner: CyclicAxis,
    pub(crate) last: Feedback,
    emcy: Option<Emcy>,
}

impl Axis {
    /// The axis of `link`, refused (typed) when the drive does not list the mode in
    /// `supported` (6502h); `window` is its following error window (6065h), if it has one.
    pub(crate) fn new(
        link: AxisLink,
        config: &CyclicConfig,
        supported: u32,
        window: Option<u32>,
    ) -> Result<Self, CyclicError> {
        let planner =
            CyclicAxis::new(config.mode, supported, config.quirks, window).map_err(|failure| {
                CyclicError::Axis {
                    node: link.node,
                    failure,
                    emcy: None,
                }
            })?;
        Ok(Self {
            link,
            planner,
            last: Feedback {
                statusword: 0,
                actual: 0,
            },
            emcy: None,
        })
    }

    /// Takes one event of the axis's subscription; true when it was a TPDO with feedback.
    pub(crate) fn take(&mut self, event: NetworkEvent) -> bool {
        match event {
            NetworkEvent::Pdo { number, frame } if number == self.link.tpdo => {
                match Feedback::from_tpdo(frame.data()) {
                    Some(feedback) => {
                        self.last = feedback;
                        true
                    }
                    None => false,
                }
            }
            NetworkEvent::Emcy(emcy) => {
                self.emcy = Some(emcy);
                false
            }
            _ => false,
        }
    }

    /// Takes the events already queued behind the fresh feedback: the newest is the state now.
    pub(crate) fn drain(&mut self, events: impl Iterator<Item = NetworkEvent>) {
        events.for_each(|event| {
            self.take(event);
        });
    }

    /// The run's failure when the axis sent no TPDO in time.
    pub(crate) fn lost(&self) -> CyclicError {
        CyclicError::FeedbackLost {
            node: self.link.node,
        }
    }

    /// `command` in the axis's RPDO.
    pub(crate) fn frame(&self, command: Command) -> Result<CanFrame, BusError> {
        let (payload, len) = command.rpdo_payload(self.planner.mode());
        CanFrame::new(self.link.rpdo_cob_id, &payload[..len])
    }

    /// The RPDO that quick-stops the axis, holding its set point.
    pub(crate) fn stop_frame(&self) -> Result<CanFrame, BusError> {
        self.frame(self.planner.stop(self.last))
    }

    /// The RPDO for the next SYNC, or the run's failure naming the axis and its last EMCY.
    fn next(&mut self, sample: Option<i32>, now: Millis) -> Result<CanFrame, CyclicError> {
        let command = self
            .planner
            .cycle(self.last, sample, now)
            .map_err(|failure| CyclicError::Axis {
                node: self.link.node,
                failure,
                emcy: self.emcy,
            })?;
        Ok(self.frame(command)?)
    }
}

/// What a shell's network manager does for a run without waiting: subscribe, send an RPDO,
/// produce SYNC. The blocking [`Network`] and the async [`AsyncNetwork`] both do it.
pub(crate) trait Pdos {
    /// The network's subscription to a node's events.
    type Events;
    /// Subscribes to `node`'s events.
    fn events(&self, node: NodeId) -> Self::Events;
    /// Queues `frame`.
    fn queue(&self, frame: CanFrame) -> Result<(), BusError>;
    /// Produces SYNC every `period`; `None` stops it.
    fn sync(&self, period: Option<Duration>);
}

/// `Pdos` for a network handle type, over its own methods of the same meaning.
macro_rules! pdos {
    ($events:ty) => {
        type Events = $events;
        fn events(&self, node: NodeId) -> $events {
            self.subscribe(node, EVENTS)
        }
        fn queue(&self, frame: CanFrame) -> Result<(), BusError> {
            self.send(frame)
        }
        fn sync(&self, period: Option<Duration>) {
            self.set_sync(period);
        }
    };
}

impl<B> Pdos for Network<B> {
    pdos!(Subscription);
}

#[cfg(feature = "async")]
impl<T> Pdos for AsyncNetwork<T> {
    pdos!(AsyncSubscription);
}

/// The events kept per axis: a few cycles' TPDOs and EMCYs.
const EVENTS: usize = 64;

/// The axes of a run, each with its subscription (of the shell's kind), and the run's
/// configuration and time origin.
#[derive(Debug)]
pub(crate) struct Axes<S> {
    pub(crate) config: CyclicConfig,
    axes: Vec<Axis>,
    events: Vec<S>,
    started: Instant,
}

impl<S> Axes<S> {
    /// The run of `axes` (set up by SDO) on `network`: subscribes to each axis's events, then
    /// starts SYNC at the period.
    pub(crate) fn start<N: Pdos<Events = S>>(
        network: &N,
        config: CyclicConfig,
        axes: Vec<Axis>,
    ) -> Self {
        let events = axes.iter().map(|a| network.events(a.link.node)).collect();
        network.sync(Some(config.period));
        Self {
            config,
            axes,
            events,
            started: Instant::now(),
        }
    }

    /// The last feedback of each axis.
    pub(crate) fn feedback(&self) -> Vec<Feedback> {
        self.axes.iter().map(|a| a.last).collect()
    }

    /// Each axis with its subscription.
    pub(crate) fn each(&mut self) -> impl Iterator<Item = (&mut Axis, &S)> {
        self.axes.iter_mut().zip(&self.events)
    }

    /// Whether any axis's last feedback still shows operation enabled (a stop not yet taken).
    pub(crate) fn any_enabled(&self) -> bool {
        self.axes
            .iter()
            .any(|a| operation_enabled(a.last.statusword))
    }

    /// Sends every axis's quick stop RPDO on `network`; a bus that fails now has nothing more
    /// to stop, so failures are passed over.
    pub(crate) fn stop(&self, network: &impl Pdos) {
        for axis in &self.axes {
            let _ = axis.stop_frame().and_then(|f| network.queue(f));
        }
    }

    /// A run of `cycles` cycles starting now.
    pub(crate) fn cycles(&self, cycles: u64) -> Cycles {
        Cycles::new(cycles, &self.config)
    }

    /// One cycle of `run` once every axis's feedback came ([`Cycles::step`]), the RPDOs sent
    /// on `network`.
    pub(crate) fn step(
        &mut self,
        run: &mut Cycles,
        sample: &mut impl FnMut(u64, usize) -> i32,
        network: &impl Pdos,
    ) -> Result<(), CyclicError> {
        run.step(&mut self.axes, self.started, sample, |f| network.queue(f))
    }
}

/// The SDO writes (index, sub-index, value) that set the mode (6060h) and the interpolation
/// period (60C2h) of an axis.
pub(crate) fn setup_writes(config: &CyclicConfig) -> [(u16, u8, [u8; 1]); 3] {
    let (value, index) = interpolation_period(config.period);
    [
        (0x6060, 0, config.mode.number().to_le_bytes()),
        (0x60C2, 1, [value]),
        (0x60C2, 2, index.to_le_bytes()),
    ]
}

/// The interpolation period 60C2h as (value, power of ten): whole milliseconds if it is, else
/// tenths of milliseconds.
fn interpolation_period(period: Duration) -> (u8, i8) {
    let micros = period.as_micros();
    if micros % 1000 == 0 && micros / 1000 <= u128::from(u8::MAX) {
        ((micros / 1000) as u8, -3)
    } else {
        ((micros / 100).min(u128::from(u8::MAX)) as u8, -4)
    }
}

/// The progress of one `run`: cycles counted once every axis follows, the enable time limit,
/// the timing of the cycles.
#[derive(Debug)]
pub(crate) struct Cycles {
    cycles: u64,
    cycle: u64,
    enable_by: Instant,
    previous: Option<Instant>,
    stats: CycleStats,
}

impl Cycles {
    /// A run of `cycles` cycles starting now.
    pub(crate) fn new(cycles: u64, config: &CyclicConfig) -> Self {
        Self {
            cycles,
            cycle: 0,
            enable_by: Instant::now() + config.enable_within,
            previous: None,
            stats: CycleStats::new(config.period),
        }
    }

    /// Whether cycles remain.
    pub(crate) fn running(&self) -> bool {
        self.cycle < self.cycles
    }

    /// Once every axis's feedback of this SYNC came: times the cycle, fails when the axes are
    /// not all enabled in time, then hands each axis's next RPDO to `send` (the sample of
    /// `sample(cycle, axis)` once all follow). `started` is the run's time origin.
    pub(crate) fn step(
        &mut self,
        axes: &mut [Axis],
        started: Instant,
        sample: &mut impl FnMut(u64, usize) -> i32,
        mut send: impl FnMut(CanFrame) -> Result<(), BusError>,
    ) -> Result<(), CyclicError> {
        let received = Instant::now();
        let following = axes.iter().all(|a| a.planner.following());
        if following {
            if let Some(previous) = self.previous {
                self.stats.record(received - previous);
            }
            self.previous = Some(received);
        } else if received >= self.enable_by {
            let node = axes.iter().find(|a| !a.planner.following());
            return Err(CyclicError::EnableTimeout {
                node: node.map_or(NodeId(0), |a| a.link.node),
            });
        }
        let now = Millis(started.elapsed().as_millis() as u64);
        for (i, axis) in axes.iter_mut().enumerate() {
            let next = following.then(|| sample(self.cycle, i));
            send(axis.next(next, now)?)?;
        }
        if following {
            self.cycle += 1;
        }
        Ok(())
    }

    /// The timing of the cycles run.
    pub(crate) fn stats(self) -> CycleStats {
        self.stats
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::control::cyclic::CyclicMode;
    use crate::control::Quirks;

    #[test]
    fn the_interpolation_period_in_milliseconds_or_tenths() {
        assert_eq!(interpolation_period(Duration::from_millis(4)), (4, -3));
        assert_eq!(interpolation_period(Duration::from_micros(1_500)), (15, -4));
    }

    #[test]
    fn an_axis_takes_its_own_tpdo_and_the_emcy_it_is_sent() {
        let link = AxisLink {
            node: NodeId(3),
            rpdo_cob_id: 0x203,
            tpdo: 1,
        };
        let config = CyclicConfig {
            mode: CyclicMode::Position,
            period: Duration::from_millis(4),
            quirks: Quirks::STANDARD,
            enable_within: Duration::from_secs(1),
            feedback_within: Duration::from_secs(1),
        };
        let mut axis = Axis::new(link, &config, 0x0380, None).unwrap();
        let tpdo = |number, data: &[u8]| NetworkEvent::Pdo {
            number,
            frame: CanFrame::new(0x183, data).unwrap(),
        };
        assert!(
            !axis.take(tpdo(2, &[0x37, 0x12, 1, 0, 0, 0])),
            "another TPDO"
        );
        assert!(!axis.take(tpdo(1, &[0x37, 0x12])), "too short");
        assert!(axis.take(tpdo(1, &[0x37, 0x12, 1, 0, 0, 0])));
        assert_eq!(axis.last.actual, 1);
        let stop = axis.stop_frame().unwrap();
        assert_eq!(
            (stop.id(), stop.data()),
            (0x203, &[0x02, 0, 1, 0, 0, 0][..])
        );
        let writes = setup_writes(&config);
        assert_eq!(writes[0], (0x6060, 0, [8]));
        assert_eq!(writes[2], (0x60C2, 2, [0xFD]));
    }
}
