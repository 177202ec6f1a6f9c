//! The quickstart runs end to end: on its embedded simulator, and with `--serial` against the
//! simulator serving Modbus RTU on a socat pty, as it would a real drive.

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

use drivebus::modbus::client::{SerialConfig, SerialStream};
use drivebus::modbus::UnitId;

/// The example binary `cargo test` builds next to the test binaries.
fn quickstart() -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let profile_dir = exe.parent().and_then(Path::parent).unwrap();
    profile_dir.join("examples").join("quickstart")
}

fn check(output: &Output) -> String {
    let stdout = String::from_utf8_lossy(&output.stdout).into_owned();
    assert!(
        output.status.success(),
        "quickstart failed:\n{stdout}\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(stdout.contains("operation mode     velocity"), "{stdout}");
    assert!(
        stdout.contains("1500 rpm"),
        "the motor reaches the setpoint: {stdout}"
    );
    assert!(
        stdout.contains("stop               DriveStatus(STOP), 0 rpm"),
        "{stdout}"
    );
    assert!(
        stdout.contains("standby            DriveStatus(STANDBY)"),
        "{stdout}"
    );
    stdout
}

#[test]
fn quickstart_runs_on_its_simulated_drive() {
    let stdout = check(&Command::new(quickstart()).output().unwrap());
    assert!(stdout.contains("49.50 V"), "{stdout}");
}

/// A child process killed by its PID and reaped when dropped.
struct Process(Child);

impl Drop for Process {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

#[test]
fn quickstart_serial_talks_rtu() {
    let dir = std::env::temp_dir().join(format!("drivegen-quickstart-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (client, server) = (dir.join("client"), dir.join("server"));
    let _socat = Process(
        Command::new("socat")
            .arg(format!("pty,raw,echo=0,link={}", client.display()))
            .arg(format!("pty,raw,echo=0,link={}", server.display()))
            .stdin(Stdio::null())
            .spawn()
            .expect("socat is needed: run tests/peers/setup.sh"),
    );
    let deadline = Instant::now() + Duration::from_secs(5);
    while !(client.exists() && server.exists()) {
        assert!(
            Instant::now() < deadline,
            "socat did not create the pty links"
        );
        std::thread::sleep(Duration::from_millis(10));
    }
    let description = Path::new(env!("CARGO_MANIFEST_DIR")).join("../descriptions/lafert-smartris");
    let sim = drivesim::Simulator::load(description).unwrap();
    // As the TCP quickstart's drive: velocity mode, and an L motor's full scale (3000 rpm) that
    // bounds the 1500 rpm set point (a drive at full scale 0 refuses it before anything is sent).
    sim.preset("operation_mode", 2)
        .unwrap()
        .preset("full_scale_velocity", 3000)
        .unwrap();
    let mut stream =
        SerialStream::open(server.to_str().unwrap(), &SerialConfig::new(19_200)).unwrap();
    // Ends with an I/O error once socat is stopped.
    std::thread::spawn(move || drivesim::modbus::rtu::serve(&sim, &mut stream, UnitId(1)));
    let output = Command::new(quickstart())
        .args(["--serial", client.to_str().unwrap()])
        .output()
        .unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    check(&output);
}
