//! python canopen 2.4.1's `BaseNode402` as an independent CiA 402 master of the simulated Kinco FD
//! (issue 32 item 5), through the EDS exported from the Kinco description
//! (tests/peers/kinco_motion_master.py at the workspace root): operation enabled, `homing()`, a
//! profile position move by SDO to 50,000 increments, target reached and the actual position
//! within the position window.

mod support;

#[test]
fn python_canopen_base_node_402_homes_and_moves_the_simulated_kinco() {
    support::python_master_passes("kinco_motion_master.py", "python canopen BaseNode402");
}
