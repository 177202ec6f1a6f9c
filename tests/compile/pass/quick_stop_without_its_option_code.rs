use drivebus::canopen::NodeId;
use drivebus::testing::MemoryBus;
use kinco_fd::KincoFd;

fn main() {
    // The Kinco describes its quick stop option code (605Ah): the handle has both stops.
    let mut drive = KincoFd::canopen(MemoryBus::new(), NodeId(1));
    let _ = drive.quick_stop(std::time::Instant::now());
    let _ = drive.quick_stop_by_option_code(std::time::Instant::now());
}
