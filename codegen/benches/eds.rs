//! EDS reading speed: a generated EDS of 2,000 objects (814 VARs and 1,186 RECORDs of 5 sub-indices:
//! 6,744 entries) read into IR parameters, side by side with python canopen 2.4.1's `import_od` on
//! the same file (codegen/benches/eds_import.py, best of 3). Target: at most 6 ms, 100× python.
#![allow(missing_docs)] // `criterion_group!` defines an undocumented public function.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

use criterion::{criterion_group, criterion_main, Criterion};
use drivegen::diagnostic::Files;

const RECORDS: u16 = 1186;
const VARS: u16 = 814;

/// An EDS of `VARS` variables and `RECORDS` records, with limits, defaults and `$NODEID` terms.
fn generated_eds() -> String {
    let mut eds = String::from(
        "[FileInfo]\nFileName=bench.eds\nEDSVersion=4.0\n\n[DeviceInfo]\nVendorName=Bench\nProductName=Bench\n",
    );
    for i in 0..VARS {
        let _ = write!(
            eds,
            "\n[{:04X}]\nParameterName=Variable {i}\nObjectType=0x7\nDataType=0x0004\nAccessType=rw\nLowLimit=-0x1000\nHighLimit=0x1000\nDefaultValue={}\nPDOMapping=1\n",
            0x2000 + i,
            i % 100
        );
    }
    for r in 0..RECORDS {
        let index = 0x3000 + r;
        let _ = write!(
            eds,
            "\n[{index:04X}]\nParameterName=Record {r}\nObjectType=0x9\nSubNumber=5\n"
        );
        let _ = write!(eds, "\n[{index:04X}sub0]\nParameterName=Highest sub-index supported\nObjectType=0x7\nDataType=0x0005\nAccessType=ro\nDefaultValue=4\nPDOMapping=0\n");
        for sub in 1..5 {
            let _ = write!(
                eds,
                "\n[{index:04X}sub{sub}]\nParameterName=Member {sub}\nObjectType=0x7\nDataType=0x0007\nAccessType=rw\nDefaultValue=$NODEID+0x{:X}\nPDOMapping=0\n",
                0x180 + sub
            );
        }
    }
    eds
}

fn read(path: &Path, bytes: &[u8]) -> usize {
    let mut files = Files::default();
    let mut diagnostics = Vec::new();
    let model = drivegen::eds::read_bytes(path, bytes, &mut files, &mut diagnostics);
    drivegen::eds::typed_parameters(model.entries, &model.cited, &mut diagnostics).len()
}

fn python() -> PathBuf {
    if let Some(python) = std::env::var_os("DRIVEGEN_PYTHON") {
        return python.into();
    }
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../.venv/bin/python")
}

/// Best of 3 `import_od` runs, in seconds.
fn python_import_od(path: &Path) -> f64 {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("benches/eds_import.py");
    let output = Command::new(python())
        .arg(script)
        .arg(path)
        .arg("3")
        .output()
        .expect("python canopen is required: run tests/peers/setup.sh or set DRIVEGEN_PYTHON");
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let fields: Vec<&str> = stdout.split_whitespace().collect();
    println!(
        "python canopen import_od: {} objects, {} entries",
        fields[1], fields[2]
    );
    fields[0].parse().expect("seconds")
}

fn eds_read(c: &mut Criterion) {
    let dir = std::env::temp_dir().join(format!("drivegen-eds-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("bench.eds");
    let text = generated_eds();
    std::fs::write(&path, &text).unwrap();
    let entries = read(&path, text.as_bytes());
    assert_eq!(entries, usize::from(VARS) + 5 * usize::from(RECORDS));
    c.bench_function("read a 2,000-object EDS into IR parameters", |b| {
        b.iter(|| read(&path, text.as_bytes()))
    });
    let best = (0..20)
        .map(|_| {
            let start = Instant::now();
            read(&path, text.as_bytes());
            start.elapsed()
        })
        .min()
        .unwrap_or(Duration::ZERO);
    let python = python_import_od(&path);
    println!(
        "drivegen: {entries} entries in {:.3} ms (best of 20); python canopen import_od: {:.1} ms; ratio {:.0}x",
        best.as_secs_f64() * 1e3,
        python * 1e3,
        python / best.as_secs_f64()
    );
    let _ = std::fs::remove_dir_all(&dir);
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10).measurement_time(Duration::from_secs(2));
    targets = eds_read
}
criterion_main!(benches);
