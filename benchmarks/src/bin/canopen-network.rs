//! The CANopen network manager (issue 31, "Performance"): reading one object from each of 32
//! nodes on one bus against reading it from one node, with the manager (blocking and async)
//! and, as "today", one `BlockingSdo` going from node to node; and a scan of all 127 node ids
//! against its timeout.
//!
//! `cargo run -p benchmarks --bin canopen-network -- [--rounds 7] [--sweeps 100]
//! [--latency-us 1000]`
//!
//! A sweep reads object 2000h:00 (4 bytes, expedited) once from each node of the set (1 node,
//! or nodes 1..=32). The 32 nodes are `drivebus` SDO servers on one in-process bus, each
//! answering `--latency-us` after a request, as a drive's firmware takes its time (every node
//! on its own, as separate devices do); the bus itself has no wire time. For the blocking
//! variants a thread serves them all, for the async ones a task on the same current-thread
//! tokio runtime that answers each batch of requests the latency after it arrived. The variants alternate within each round; the figure that counts is the
//! ratio 32 nodes / 1 node of the same variant and round. Prints Markdown.

use std::collections::{BTreeMap, VecDeque};
use std::future::Future;
use std::pin::{pin, Pin};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Barrier};
use std::task::{Context, Poll, Waker};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use benchmarks::flags::Flags;
use benchmarks::process::load_average;
use drivebus::asynch::TokioTimer;
use drivebus::canopen::can::async_in_process::{AsyncInProcessBus, AsyncInProcessEndpoint};
use drivebus::canopen::can::in_process::InProcessBus;
use drivebus::canopen::can::AsyncCanBus;
use drivebus::canopen::client::scan::scan;
use drivebus::canopen::client::BlockingSdo;
use drivebus::canopen::network::{AsyncNetwork, Network};
use drivebus::canopen::sdo::server::SdoServer;
use drivebus::canopen::{AsyncSdoBus, CanBus, CanFrame, NodeId, SdoBus};

const NODES: u8 = 32;
const TIMEOUT: Duration = Duration::from_millis(500);

type Dictionary = BTreeMap<(u16, u8), Vec<u8>>;

/// How long a node takes to answer, set once from `--latency-us`.
static LATENCY_US: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1000);

fn latency() -> Duration {
    Duration::from_micros(LATENCY_US.load(Ordering::Relaxed))
}

fn servers() -> Vec<SdoServer<Dictionary>> {
    (1..=NODES)
        .map(|id| {
            let mut dictionary = Dictionary::new();
            dictionary.insert((0x1000, 0), 0x0002_0192u32.to_le_bytes().to_vec());
            dictionary.insert((0x2000, 0), u32::from(id).to_le_bytes().to_vec());
            SdoServer::new(NodeId(id), dictionary)
        })
        .collect()
}

/// The 32 servers on one endpoint of `bus`, in a thread, until dropped.
struct Served {
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
}

impl Served {
    fn start(bus: &InProcessBus) -> Self {
        let mut endpoint = bus.endpoint();
        let stop = Arc::new(AtomicBool::new(false));
        let flag = Arc::clone(&stop);
        let thread = std::thread::spawn(move || {
            let mut servers = servers();
            let mut due: VecDeque<(Instant, CanFrame)> = VecDeque::new();
            while !flag.load(Ordering::Relaxed) {
                let wait = due.front().map_or(Duration::from_millis(10), |(at, _)| {
                    at.saturating_duration_since(Instant::now())
                });
                if let Ok(Some(frame)) = endpoint.recv(wait) {
                    let at = Instant::now() + latency();
                    due.extend(
                        servers
                            .iter_mut()
                            .flat_map(|s| s.handle(&frame))
                            .map(|a| (at, a)),
                    );
                }
                while due.front().is_some_and(|(at, _)| *at <= Instant::now()) {
                    let (_, answer) = due.pop_front().unwrap();
                    let _ = endpoint.send(&answer);
                }
            }
        });
        Self {
            stop,
            thread: Some(thread),
        }
    }
}

impl Drop for Served {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}

fn read(sdo: &mut impl SdoBus, node: u8) {
    let mut out = [0u8; 4];
    let len = sdo.upload(NodeId(node), 0x2000, 0, &mut out).unwrap();
    assert_eq!((len, u32::from_le_bytes(out)), (4, u32::from(node)));
}

/// Time per sweep of one `BlockingSdo` reading each node in turn.
fn today(nodes: u8, sweeps: u32) -> Duration {
    let bus = InProcessBus::new();
    let _served = Served::start(&bus);
    let mut sdo = BlockingSdo::new(bus.endpoint()).with_timeout(TIMEOUT);
    let start = Instant::now();
    for _ in 0..sweeps {
        (1..=nodes).for_each(|node| read(&mut sdo, node));
    }
    start.elapsed() / sweeps
}

/// Time per sweep of the blocking manager: one thread per node, all reading at once.
fn blocking(nodes: u8, sweeps: u32) -> Duration {
    let bus = InProcessBus::new();
    let _served = Served::start(&bus);
    let network = Network::new(bus.endpoint());
    let barrier = Arc::new(Barrier::new(usize::from(nodes) + 1));
    let workers: Vec<_> = (1..=nodes)
        .map(|node| {
            let mut sdo = network.node(NodeId(node)).with_timeout(TIMEOUT);
            let barrier = Arc::clone(&barrier);
            std::thread::spawn(move || {
                for _ in 0..sweeps {
                    barrier.wait();
                    read(&mut sdo, node);
                    barrier.wait();
                }
            })
        })
        .collect();
    let mut total = Duration::ZERO;
    for _ in 0..sweeps {
        barrier.wait();
        let start = Instant::now();
        barrier.wait();
        total += start.elapsed();
    }
    workers.into_iter().for_each(|w| w.join().unwrap());
    total / sweeps
}

/// Every future of `futures` to its end, polled together.
async fn join_all(mut futures: Vec<Pin<Box<dyn Future<Output = ()> + '_>>>) {
    let mut done = vec![false; futures.len()];
    std::future::poll_fn(|cx| {
        for (future, done) in futures.iter_mut().zip(done.iter_mut()) {
            if !*done {
                *done = future.as_mut().poll(cx).is_ready();
            }
        }
        if done.iter().all(|d| *d) {
            Poll::Ready(())
        } else {
            Poll::Pending
        }
    })
    .await;
}

/// The 32 servers as a task on `endpoint`: each batch of requests (what has arrived when the
/// task runs) is answered the latency after its first request. The wait is a thread sleep, not
/// a tokio timer (whose 1 ms resolution would add up to a millisecond to every answer); the
/// runtime pauses meanwhile, when the manager has sent all it had and waits for answers anyway.
async fn serve_async(mut endpoint: AsyncInProcessEndpoint) {
    let mut servers = servers();
    while let Ok(first) = endpoint.recv().await {
        let arrived = Instant::now();
        let mut batch = vec![first];
        let mut cx = Context::from_waker(Waker::noop());
        while let Poll::Ready(Ok(frame)) = pin!(endpoint.recv()).poll(&mut cx) {
            batch.push(frame);
        }
        let answers: Vec<CanFrame> = batch
            .iter()
            .flat_map(|frame| {
                servers
                    .iter_mut()
                    .flat_map(|s| s.handle(frame))
                    .collect::<Vec<_>>()
            })
            .collect();
        std::thread::sleep(latency().saturating_sub(arrived.elapsed()));
        for answer in answers {
            let _ = endpoint.send(&answer).await;
        }
    }
}

/// Time per sweep of the async manager: one future per node, joined, on a current-thread
/// runtime that also runs the servers.
fn asynchronous(nodes: u8, sweeps: u32) -> Duration {
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_time()
        .build()
        .unwrap();
    runtime.block_on(async {
        let bus = AsyncInProcessBus::new();
        let server = serve_async(bus.endpoint());
        let (network, mut router) = AsyncNetwork::new(bus.endpoint(), TokioTimer);
        let work = async {
            let mut handles: Vec<_> = (1..=nodes)
                .map(|node| network.node(NodeId(node)).with_timeout(TIMEOUT))
                .collect();
            let start = Instant::now();
            for _ in 0..sweeps {
                let reads = handles
                    .iter_mut()
                    .map(|sdo| {
                        Box::pin(async move {
                            let node = sdo.node().get();
                            let mut out = [0u8; 4];
                            let len = sdo.upload(NodeId(node), 0x2000, 0, &mut out).await;
                            assert_eq!(len, Ok(4));
                            assert_eq!(u32::from_le_bytes(out), u32::from(node));
                        }) as Pin<Box<dyn Future<Output = ()>>>
                    })
                    .collect();
                join_all(reads).await;
            }
            let elapsed = start.elapsed();
            network.close();
            elapsed
        };
        let (mut routed, mut elapsed) = (None, None);
        join_all(vec![
            Box::pin(async {
                routed = Some(router.run().await);
                // Ends the server task, once the router let go of the bus.
                bus.close();
            }),
            Box::pin(async { elapsed = Some(work.await) }),
            Box::pin(server),
        ])
        .await;
        routed.unwrap().unwrap();
        elapsed.unwrap() / sweeps
    })
}

/// A scan of node ids 1..=127 with 32 nodes present: its time and the nodes found.
fn scan_all(timeout: Duration) -> (Duration, usize) {
    let bus = InProcessBus::new();
    let _served = Served::start(&bus);
    let mut endpoint = bus.endpoint();
    let all: Vec<NodeId> = (1..=127).map(NodeId).collect();
    let start = Instant::now();
    let found = scan(&mut endpoint, &all, timeout).unwrap();
    (start.elapsed(), found.len())
}

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

type Variant = (&'static str, fn(u8, u32) -> Duration);

fn main() -> Result<(), String> {
    let mut flags = Flags::from_env()?;
    let rounds = u32::try_from(flags.number("--rounds", 7)?).map_err(|e| e.to_string())?;
    let sweeps = u32::try_from(flags.number("--sweeps", 100)?).map_err(|e| e.to_string())?;
    LATENCY_US.store(flags.number("--latency-us", 1000)?, Ordering::Relaxed);
    flags.finish()?;
    let variants: [Variant; 3] = [
        ("today: one BlockingSdo, node after node", today),
        ("Network (blocking, a thread per node)", blocking),
        (
            "AsyncNetwork (a future per node, current-thread tokio)",
            asynchronous,
        ),
    ];
    println!(
        "node latency {} µs, {sweeps} sweeps per variant and round; load average before: {}\n",
        latency().as_micros(),
        load_average()
    );
    let mut results: Vec<Vec<(f64, f64)>> = vec![Vec::new(); variants.len()];
    for round in 0..rounds as usize {
        for k in 0..variants.len() {
            let which = (round + k) % variants.len();
            let (_, run) = variants[which];
            let one = run(1, sweeps).as_secs_f64() * 1e6;
            let many = run(NODES, sweeps).as_secs_f64() * 1e6;
            results[which].push((one, many));
        }
    }
    println!("| variant | 1 node µs/sweep | 32 nodes µs/sweep | 32 / 1, per round | median |");
    println!("| --- | ---: | ---: | --- | ---: |");
    for ((name, _), rounds) in variants.iter().zip(&results) {
        let ratios: Vec<f64> = rounds.iter().map(|(one, many)| many / one).collect();
        let listed: Vec<String> = ratios.iter().map(|r| format!("{r:.2}")).collect();
        println!(
            "| {name} | {:.0} | {:.0} | {} | **{:.2}** |",
            median(rounds.iter().map(|r| r.0).collect()),
            median(rounds.iter().map(|r| r.1).collect()),
            listed.join(", "),
            median(ratios),
        );
    }
    println!();
    for timeout_ms in [100u64, 200] {
        let timeout = Duration::from_millis(timeout_ms);
        let (took, found) = scan_all(timeout);
        println!(
            "scan of node ids 1-127, {found} present, timeout {timeout_ms} ms: {:.0} ms ({:.2} timeouts)",
            took.as_secs_f64() * 1e3,
            took.as_secs_f64() / timeout.as_secs_f64()
        );
    }
    println!("\nload average after: {}", load_average());
    Ok(())
}
