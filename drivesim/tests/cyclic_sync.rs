//! The simulated axis in the cyclic synchronous modes, on the example CiA 402 axis: in CSP each
//! target position is reached evenly over one interpolation period (60C2h), statusword bit 12
//! says the drive follows, bit 13 a following error; in CSV the position integrates the target
//! velocity; in CST the torque set points drive the simulated load. Time is advanced by hand.

use std::time::Duration;

use drivesim::Drive;

const AXIS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/csp_axis");

const FOLLOWS: u16 = 1 << 12;
const FOLLOWING_ERROR: u16 = 1 << 13;

fn drive() -> Drive {
    let checked = drivegen::check(std::path::Path::new(AXIS));
    let report = checked.render();
    Drive::new(checked.device.unwrap_or_else(|| panic!("{report}")))
}

fn set(drive: &mut Drive, name: &str, value: i64) {
    let id = drive.store().id(name).unwrap_or_else(|| panic!("{name}"));
    let width = drive.store().bytes(id).len();
    drive
        .write(id, &value.to_le_bytes()[..width])
        .unwrap_or_else(|e| panic!("{name} = {value}: {e:?}"));
}

fn get(drive: &Drive, name: &str) -> i128 {
    let id = drive.store().id(name).unwrap();
    drive.store().int(id).unwrap()
}

fn enabled(mode: i64) -> Drive {
    let mut drive = drive();
    set(&mut drive, "modes_of_operation", mode);
    for word in [0x06, 0x07, 0x0F] {
        set(&mut drive, "controlword", word);
    }
    drive
}

const MS: Duration = Duration::from_millis(1);

#[test]
fn csp_reaches_each_set_point_evenly_over_the_interpolation_period() {
    let mut drive = enabled(8);
    let status = get(&drive, "statusword") as u16;
    assert_eq!(status & 0x6F, 0x27, "operation enabled: {status:#06X}");
    assert_ne!(status & FOLLOWS, 0, "follows the command value");
    // The period is 4 ms: 400 units at 100 000 units/s.
    set(&mut drive, "target_position", 400);
    drive.tick(2 * MS);
    assert_eq!(get(&drive, "position_actual_value"), 200, "half way");
    assert_eq!(get(&drive, "velocity_actual_value"), 100_000);
    drive.tick(3 * MS);
    assert_eq!(get(&drive, "position_actual_value"), 400, "stands on it");
    assert_eq!(get(&drive, "velocity_actual_value"), 0);
    set(&mut drive, "target_position", 0);
    drive.tick(4 * MS);
    assert_eq!(get(&drive, "position_actual_value"), 0);
    assert_eq!(get(&drive, "statusword") as u16 & FOLLOWING_ERROR, 0);
}

#[test]
fn csp_reports_a_following_error_beyond_its_window_and_time_out() {
    let mut drive = enabled(8);
    drive.block_load(true);
    // 5 000 units away: beyond the 2 000 window for longer than 10 ms.
    set(&mut drive, "target_position", 5_000);
    drive.tick(4 * MS);
    drive.tick(4 * MS);
    assert_eq!(
        get(&drive, "statusword") as u16 & FOLLOWING_ERROR,
        0,
        "within time out"
    );
    drive.tick(8 * MS);
    assert_ne!(get(&drive, "statusword") as u16 & FOLLOWING_ERROR, 0);
}

#[test]
fn csv_integrates_the_target_velocity_and_nothing_moves_unless_enabled() {
    let mut drive = enabled(9);
    assert_ne!(get(&drive, "statusword") as u16 & FOLLOWS, 0);
    set(&mut drive, "target_velocity", 10_000);
    drive.tick(Duration::from_millis(100));
    let position = get(&drive, "position_actual_value");
    assert!((990..=1_010).contains(&position), "{position}");

    let mut idle = drive_disabled();
    set(&mut idle, "target_position", 400);
    idle.tick(4 * MS);
    assert_eq!(get(&idle, "position_actual_value"), 0);
}

#[test]
fn cst_drives_the_load_with_the_target_torque() {
    let mut drive = enabled(10);
    assert_ne!(get(&drive, "statusword") as u16 & FOLLOWS, 0);
    set(&mut drive, "target_torque", 10);
    drive.tick(Duration::from_secs(3));
    // dv/dt = 1000 · torque − 2 · v settles at 5 000 units/s (drivesim::behaviour::torque).
    let speed = get(&drive, "velocity_actual_value");
    assert!((4_900..=5_000).contains(&speed), "{speed}");
    let position = get(&drive, "position_actual_value");
    set(&mut drive, "target_torque", -10);
    drive.tick(Duration::from_secs(3));
    assert!(get(&drive, "velocity_actual_value") < -4_900);
    assert!(
        get(&drive, "position_actual_value") < position,
        "driven back"
    );
}

fn drive_disabled() -> Drive {
    let mut drive = drive();
    set(&mut drive, "modes_of_operation", 8);
    drive
}

mod over_canopen {
    //! The runtime's cyclic driver against two simulated axes on one in-process bus.

    use std::time::Duration;

    use drivebus::canopen::can::in_process::InProcessBus;
    use drivebus::canopen::network::Network;
    use drivebus::canopen::nmt::NmtCommand;
    use drivebus::canopen::NodeId;
    use drivebus::control::cyclic::{CyclicFailure, CyclicMode, Feedback};
    use drivebus::control::cyclic_driver::{AxisLink, CyclicConfig, CyclicError, CyclicRun};
    use drivebus::control::Quirks;
    use drivesim::canopen::{InProcessNode, NodeConfig};
    use drivesim::Simulator;

    use super::AXIS;

    pub(super) const LINKS: [AxisLink; 2] = [
        AxisLink {
            node: NodeId(1),
            rpdo_cob_id: 0x201,
            tpdo: 1,
        },
        AxisLink {
            node: NodeId(2),
            rpdo_cob_id: 0x202,
            tpdo: 1,
        },
    ];

    pub(super) fn config(mode: CyclicMode) -> CyclicConfig {
        CyclicConfig {
            mode,
            period: Duration::from_millis(4),
            quirks: Quirks::STANDARD,
            enable_within: Duration::from_secs(2),
            feedback_within: Duration::from_secs(1),
        }
    }

    fn axes() -> (Vec<Simulator>, InProcessBus, InProcessNode) {
        let sims: Vec<Simulator> = (0..2).map(|_| Simulator::load(AXIS).unwrap()).collect();
        let bus = InProcessBus::new();
        let running = InProcessNode::serve(&bus, served(&sims));
        (sims, bus, running)
    }

    /// Each simulated axis with the node configuration of its link.
    pub(super) fn served(sims: &[Simulator]) -> Vec<(Simulator, NodeConfig)> {
        let config = |link: AxisLink| NodeConfig {
            node: link.node,
            heartbeat: None,
        };
        sims.iter().cloned().zip(LINKS.map(config)).collect()
    }

    pub(super) fn int(sim: &Simulator, name: &str) -> i128 {
        sim.with(|d| d.store().int(d.store().id(name).unwrap()).unwrap())
    }

    #[test]
    fn a_mode_an_axis_does_not_list_is_refused_before_anything_is_sent() {
        let (sims, bus, _running) = axes();
        sims[1].preset("supported_drive_modes", 0x0180).unwrap();
        let network = Network::new(bus.endpoint());
        network.nmt(NmtCommand::Start, None).unwrap();
        let error = CyclicRun::start(&network, &LINKS, config(CyclicMode::Torque)).unwrap_err();
        refused(&sims, error);
    }

    /// Checks `error` refuses cst on node 2, which lists only csp and csv, and no axis got a
    /// mode.
    pub(super) fn refused(sims: &[Simulator], error: CyclicError) {
        assert_eq!(
            error,
            CyclicError::Axis {
                node: NodeId(2),
                failure: CyclicFailure::ModeNotSupported {
                    mode: CyclicMode::Torque,
                    supported: 0x0180
                },
                emcy: None
            }
        );
        for sim in sims {
            assert_eq!(int(sim, "modes_of_operation"), 0, "no mode written");
        }
    }

    #[test]
    fn two_axes_follow_and_a_blocked_load_stops_the_run_with_a_following_error() {
        let (sims, bus, _running) = axes();
        let network = Network::new(bus.endpoint());
        network.nmt(NmtCommand::Start, None).unwrap();
        let mut run = CyclicRun::start(&network, &LINKS, config(CyclicMode::Position)).unwrap();
        run.run(50, |cycle, _| (cycle as i32 + 1) * 100).unwrap();
        followed(&run.feedback());
        sims[0].with(|d| d.block_load(true));
        let error = run.run(100, |cycle, _| 5_000 + (cycle as i32 + 1) * 200);
        stopped(&sims, error.map(|_| ()));
    }

    /// Checks the last TPDO of each axis shows it on one of the last set points (100 apart,
    /// the last 5 000), or on its way between them when a SYNC came early.
    pub(super) fn followed(feedback: &[Feedback]) {
        for feedback in feedback {
            assert!((4_500..=5_000).contains(&feedback.actual), "{feedback:?}");
        }
    }

    /// Checks the run stopped with node 1's following error, and quick-stopped every axis:
    /// quick stop active (or further on), no longer operation enabled.
    pub(super) fn stopped(sims: &[Simulator], error: Result<(), CyclicError>) {
        assert!(
            matches!(
                error,
                Err(CyclicError::Axis {
                    node: NodeId(1),
                    failure: CyclicFailure::FollowingError { .. },
                    ..
                })
            ),
            "{error:?}"
        );
        for sim in sims {
            let status = int(sim, "statusword") as u16;
            assert_ne!(status & 0x6F, 0x27, "{status:#06X}");
        }
    }

    #[test]
    fn csv_runs_both_axes_at_the_target_velocity_through_rpdo_2() {
        let (_sims, bus, _running) = axes();
        let network = Network::new(bus.endpoint());
        network.nmt(NmtCommand::Start, None).unwrap();
        let links = LINKS.map(|link| AxisLink {
            rpdo_cob_id: 0x300 + u16::from(link.node.0),
            ..link
        });
        let mut run = CyclicRun::start(&network, &links, config(CyclicMode::Velocity)).unwrap();
        let start: Vec<i32> = run.feedback().iter().map(|f| f.actual).collect();
        run.run(50, |_, _| 50_000).unwrap();
        for (feedback, start) in run.feedback().iter().zip(start) {
            // 50 000 units/s for at least 50 periods of 4 ms: 10 000 or more.
            assert!(feedback.actual - start >= 9_000, "{feedback:?}");
        }
        run.stop();
    }

    #[test]
    fn cst_drives_both_axes_against_their_load_through_rpdo_3() {
        let (sims, bus, _running) = axes();
        let network = Network::new(bus.endpoint());
        network.nmt(NmtCommand::Start, None).unwrap();
        let links = LINKS.map(|link| AxisLink {
            rpdo_cob_id: 0x400 + u16::from(link.node.0),
            ..link
        });
        let mut run = CyclicRun::start(&network, &links, config(CyclicMode::Torque)).unwrap();
        let start: Vec<i32> = run.feedback().iter().map(|f| f.actual).collect();
        run.run(50, |_, _| 10).unwrap();
        for ((feedback, start), sim) in run.feedback().iter().zip(start).zip(&sims) {
            // 10 torque units for at least 0.2 s: the load runs forward (v = 5 000 (1 − e^-2t)).
            assert!(feedback.actual - start >= 50, "{feedback:?}");
            assert_eq!(int(sim, "target_torque"), 10, "taken from RPDO 3");
            assert!(int(sim, "velocity_actual_value") > 1_000);
        }
        run.run(50, |_, _| -10).unwrap();
        for sim in &sims {
            assert!(int(sim, "velocity_actual_value") < 0, "braked and reversed");
        }
        run.stop();
    }
}

mod over_async_canopen {
    //! The runtime's async cyclic shell against two simulated axes, the async network manager
    //! over SLCAN on a loopback TCP connection (the axes on the blocking SLCAN bus).

    use std::net::TcpListener;

    use drivebus::asynch::TokioTimer;
    use drivebus::canopen::can::async_slcan::AsyncSlcanBus;
    use drivebus::canopen::can::slcan::SlcanBus;
    use drivebus::canopen::network::AsyncNetwork;
    use drivebus::canopen::nmt::NmtCommand;
    use drivebus::control::async_cyclic_driver::AsyncCyclicRun;
    use drivebus::control::cyclic::CyclicMode;
    use drivesim::canopen::{nodes, Node};
    use drivesim::Simulator;

    use super::over_canopen::{config, followed, refused, served, stopped, LINKS};
    use super::AXIS;

    /// Two simulated axes served over SLCAN on a loopback port from a thread that ends when
    /// the master hangs up; the master's async bus connected to them.
    async fn axes() -> (
        Vec<Simulator>,
        AsyncSlcanBus<drivebus::canopen::can::tokio_adapters::TokioIo<tokio::net::TcpStream>>,
    ) {
        let sims: Vec<Simulator> = (0..2).map(|_| Simulator::load(AXIS).unwrap()).collect();
        let served = served(&sims);
        let listener = TcpListener::bind("127.0.0.1:0").unwrap();
        let address = listener.local_addr().unwrap();
        std::thread::spawn(move || {
            let (stream, _) = listener.accept().unwrap();
            let mut bus = SlcanBus::tcp(stream).unwrap();
            let mut nodes: Vec<Node> = served
                .into_iter()
                .map(|(sim, config)| Node::new(sim.clone(), config, sim.variant()))
                .collect();
            // Ends with an error once the master hung up; that is how a test ends.
            let _ = nodes::run_while(&mut nodes, &mut bus, || true);
        });
        (sims, AsyncSlcanBus::connect(address).await.unwrap())
    }

    #[tokio::test]
    async fn a_mode_an_axis_does_not_list_is_refused_before_anything_is_sent() {
        let (sims, bus) = axes().await;
        sims[1].preset("supported_drive_modes", 0x0180).unwrap();
        let (network, mut router) = AsyncNetwork::new(bus, TokioTimer);
        let work = async {
            network.nmt(NmtCommand::Start, None).unwrap();
            let started = AsyncCyclicRun::start(&network, &LINKS, config(CyclicMode::Torque)).await;
            let error = started.map(|_| ()).unwrap_err();
            network.close();
            error
        };
        let (routed, error) = tokio::join!(router.run(), work);
        routed.unwrap();
        refused(&sims, error);
    }

    #[tokio::test]
    async fn two_axes_follow_and_a_blocked_load_stops_the_run_with_a_following_error() {
        let (sims, bus) = axes().await;
        let (network, mut router) = AsyncNetwork::new(bus, TokioTimer);
        let work = async {
            network.nmt(NmtCommand::Start, None).unwrap();
            let mut run = AsyncCyclicRun::start(&network, &LINKS, config(CyclicMode::Position))
                .await
                .unwrap();
            let stats = run.run(50, |cycle, _| (cycle as i32 + 1) * 100).await;
            let followed_feedback = run.feedback();
            sims[0].with(|d| d.block_load(true));
            let error = run
                .run(100, |cycle, _| 5_000 + (cycle as i32 + 1) * 200)
                .await;
            drop(run);
            network.close();
            (stats, followed_feedback, error)
        };
        let (routed, (stats, followed_feedback, error)) = tokio::join!(router.run(), work);
        routed.unwrap();
        assert_eq!(stats.unwrap().cycles(), 49, "intervals between 50 cycles");
        followed(&followed_feedback);
        stopped(&sims, error.map(|_| ()));
    }
}
