//! The simulated smd (drivesim, built from the same description) the simulator tests start from.

use drivesim::Simulator;

/// A simulated PC507 smd under Modbus control (C01 = 11) with these further presets.
pub fn pc507_under_modbus(presets: &[(&str, i128)]) -> Simulator {
    let sim = Simulator::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../descriptions/lenze-smd"
    ))
    .unwrap();
    sim.preset("parameter_configuration", 507).unwrap();
    sim.preset("control_source", 11).unwrap();
    for (name, value) in presets {
        sim.preset(name, *value).unwrap();
    }
    sim
}
