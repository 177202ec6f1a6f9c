//! python canopen 2.4.1 as an independent SDO master of the simulated Kinco FD, through the EDS
//! exported from the Kinco description (tests/peers/kinco_sdo_master.py at the workspace root).

mod support;

#[test]
fn python_canopen_reads_and_writes_through_the_exported_eds() {
    support::python_master_passes("kinco_sdo_master.py", "python canopen master");
}
