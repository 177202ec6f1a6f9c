//! Generator speed: load + validate + emit every shipped description (target: under 50 ms for all
//! together in release). Reported with the load+validate step alone as the baseline ratio, and
//! the emit stages (tokens, `syn` parse, prettyplease) each on their own.
#![allow(missing_docs)] // `criterion_group!` defines an undocumented public function.

use std::path::{Path, PathBuf};

use criterion::{criterion_group, criterion_main, Criterion};

fn shipped() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../descriptions");
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&root)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.join("device.toml").is_file())
        // `DRIVEGEN_BENCH_ONLY=lafert-smartris`: one family, to compare against older trees.
        .filter(|p| match std::env::var("DRIVEGEN_BENCH_ONLY") {
            Ok(only) => p.ends_with(only),
            Err(_) => true,
        })
        .collect();
    paths.sort();
    paths
}

fn generate_all(c: &mut Criterion) {
    let paths = shipped();
    c.bench_function("check all shipped descriptions", |b| {
        b.iter(|| {
            paths
                .iter()
                .map(|p| drivegen::check(p).device.map_or(0, |d| d.parameters.len()))
                .sum::<usize>()
        })
    });
    c.bench_function("check + emit Rust for all shipped descriptions", |b| {
        b.iter(|| {
            paths
                .iter()
                .map(|p| {
                    let device = drivegen::check(p)
                        .device
                        .expect("shipped descriptions are valid");
                    drivegen::emit::rust::generate(&device, "bench").len()
                })
                .sum::<usize>()
        })
    });
}

/// The three emit stages alone, over already-checked models: where the emit time goes.
fn stages(c: &mut Criterion) {
    let devices: Vec<_> = shipped()
        .iter()
        .map(|p| {
            drivegen::check(p)
                .device
                .expect("shipped descriptions are valid")
        })
        .collect();
    let tokens: Vec<_> = devices.iter().map(drivegen::emit::rust::tokens).collect();
    let files: Vec<syn::File> = tokens
        .iter()
        .map(|t| syn::parse2(t.clone()).unwrap())
        .collect();
    c.bench_function("stage: build tokens", |b| {
        b.iter(|| {
            devices
                .iter()
                .map(|d| drivegen::emit::rust::tokens(d).is_empty() as usize)
                .sum::<usize>()
        })
    });
    c.bench_function("stage: syn parse", |b| {
        b.iter(|| {
            tokens
                .iter()
                .map(|t| syn::parse2::<syn::File>(t.clone()).unwrap().items.len())
                .sum::<usize>()
        })
    });
    c.bench_function("stage: prettyplease", |b| {
        b.iter(|| {
            files
                .iter()
                .map(|f| prettyplease::unparse(f).len())
                .sum::<usize>()
        })
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20).measurement_time(std::time::Duration::from_secs(3));
    targets = generate_all, stages
}
criterion_main!(benches);
