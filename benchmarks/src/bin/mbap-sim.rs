//! `mbap-sim DRIVES`: simulated Modbus TCP drives for the async benchmarks
//! (`benchmarks::mbap_sim`). Prints the listeners' ports on one line, then serves until its
//! standard input closes (the benchmark that started it ended).

use std::io::{BufRead, Write};

fn main() -> std::io::Result<()> {
    let drives = std::env::args()
        .nth(1)
        .and_then(|n| n.parse().ok())
        .unwrap_or(1);
    let listeners = benchmarks::mbap_sim::bind(drives)?;
    let ports: Vec<String> = listeners
        .iter()
        .map(|l| l.local_addr().map(|a| a.port().to_string()))
        .collect::<Result<_, _>>()?;
    let mut out = std::io::stdout().lock();
    writeln!(out, "{}", ports.join(" "))?;
    out.flush()?;
    drop(out);
    // Stop when the parent goes away: its end of the pipe closes.
    std::thread::spawn(|| {
        let _ = std::io::stdin().lock().lines().count();
        std::process::exit(0);
    });
    tokio::runtime::Builder::new_current_thread()
        .enable_io()
        .build()?
        .block_on(benchmarks::mbap_sim::serve(listeners))
}
