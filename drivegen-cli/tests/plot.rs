//! `--plot FILE.svg` / `FILE.html` on `trace` and `watch`: a snapshot of a small plot from a
//! fixed candump log, the same bytes on every run, a plot path that cannot be written refused
//! before the bus is opened, and headless Chromium opening the HTML page: the series are in its
//! DOM and its script ran without a console error.

mod support;

use std::net::TcpListener;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::{AtomicUsize, Ordering};

use support::{drivegen, stderr, stdout};

/// Controlword writes (a flags word, no unit), two target positions (inc) and the mode (an
/// enumeration), each at its own time, a frame of an unknown node and a line that is not a frame.
const LOG: &str = "\
(1700000000.000000) can0 601#2B4060000F000000
(1700000000.001000) can0 581#604060000F000000
(1700000000.002000) can0 601#2F60600001000000
(1700000000.004000) can0 601#237A600050C30000
not a frame
(1700000000.006000) can0 601#2B4060001F000000
(1700000000.008000) can0 601#2F60600006000000
(1700000000.010000) can0 601#237A6000A0860100
(1700000000.010500) can0 7F1#05
";

fn kinco() -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../descriptions/kinco-fd");
    path.to_str().unwrap().to_owned()
}

/// A fresh scratch folder with the log in it (tests run side by side).
fn scratch() -> PathBuf {
    static NEXT: AtomicUsize = AtomicUsize::new(0);
    let n = NEXT.fetch_add(1, Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("drivegen-plot-{}-{n}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("capture.log"), LOG).unwrap();
    dir
}

/// `trace --plot NAME` of the log; the plot's text.
fn trace_plot(dir: &Path, name: &str) -> String {
    let plot = dir.join(name);
    let log = dir.join("capture.log");
    let output = drivegen(&[
        "trace",
        &kinco(),
        log.to_str().unwrap(),
        "--plot",
        plot.to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(
        stdout(&output).contains("write target_position"),
        "the lines still printed"
    );
    std::fs::read_to_string(plot).unwrap()
}

/// Compares with `tests/snapshots/NAME`; `DRIVEGEN_BLESS=1` writes it instead.
fn assert_snapshot(name: &str, actual: &str) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/snapshots")
        .join(name);
    if std::env::var_os("DRIVEGEN_BLESS").is_some() {
        std::fs::write(&path, actual).unwrap();
        return;
    }
    let expected = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (DRIVEGEN_BLESS=1 writes it)", path.display()));
    assert!(
        expected == actual,
        "{} differs (DRIVEGEN_BLESS=1 rewrites it); got:\n{actual}",
        path.display()
    );
}

#[test]
fn a_trace_plot_is_a_panel_per_parameter_in_its_unit_and_the_same_bytes_every_time() {
    let dir = scratch();
    let svg = trace_plot(&dir, "trace.svg");
    assert_eq!(svg, trace_plot(&dir, "again.svg"), "same input, same bytes");
    for panel in ["controlword", "modes_of_operation", "target_position"] {
        assert!(svg.contains(&format!(r#"<g class="panel" data-parameter="{panel}">"#)));
    }
    assert!(
        svg.contains(">target_position (inc)</text>"),
        "the unit in the title"
    );
    assert!(
        svg.contains(">position</text>"),
        "an enumeration's axis by name"
    );
    assert_snapshot("trace_plot.svg.snap", &svg);
    let html = trace_plot(&dir, "trace.html");
    assert!(
        html.contains(svg.trim_end()),
        "the page holds the same drawing"
    );
    for loads in ["src=", "href=", "@import", "url(", "https:"] {
        assert!(!html.contains(loads), "the page loads nothing: {loads}");
    }
    assert_snapshot("trace_plot.html.snap", &html);
    std::fs::remove_dir_all(dir).unwrap();
}

/// A listener nobody may connect to: the bus of a command that must refuse before opening it.
fn untouched_bus() -> (TcpListener, String) {
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    listener.set_nonblocking(true).unwrap();
    let addr = listener.local_addr().unwrap().to_string();
    (listener, addr)
}

fn assert_untouched(listener: &TcpListener) {
    match listener.accept() {
        Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => {}
        other => panic!("the bus was opened: {other:?}"),
    }
}

#[test]
fn a_plot_path_that_cannot_be_written_is_refused_before_the_bus_is_opened() {
    let dir = scratch();
    let unwritable = dir.join("no-such-folder/plot.svg");
    let unwritable = unwritable.to_str().unwrap();
    let wrong_kind = dir.join("plot.png");
    let wrong_kind = wrong_kind.to_str().unwrap();
    for (plot, says) in [
        (unwritable, "cannot be written"),
        (wrong_kind, "must end in .svg or .html"),
    ] {
        let (listener, addr) = untouched_bus();
        let can = format!("slcan:{addr}");
        let trace = drivegen(&["trace", &kinco(), "--can", &can, "--plot", plot]);
        assert!(!trace.status.success());
        assert!(stderr(&trace).contains(says), "{}", stderr(&trace));
        assert_untouched(&listener);
        let watch = drivegen(&[
            "watch",
            &kinco(),
            "statusword",
            "--can",
            &can,
            "--node-id",
            "1",
            "--plot",
            plot,
        ]);
        assert!(!watch.status.success());
        assert!(stderr(&watch).contains(says), "{}", stderr(&watch));
        assert_untouched(&listener);
    }
    std::fs::remove_dir_all(dir).unwrap();
}

/// Headless Chromium as `/work/shared/notes/test-peers.md` runs it, with the page's console on
/// standard error.
fn chromium(dir: &Path, page: &Path) -> (String, String) {
    let profile = dir.join("chromium-profile");
    std::fs::create_dir_all(&profile).unwrap();
    let output = Command::new("chromium")
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-background-networking",
            "--no-first-run",
            "--enable-logging=stderr",
            "--v=0",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .arg("--dump-dom")
        .arg(format!("file://{}", page.display()))
        .output()
        .unwrap_or_else(|e| panic!("chromium: {e}; {}", peer_support::SETUP_HINT));
    assert!(output.status.success(), "{}", stderr(&output));
    (
        String::from_utf8_lossy(&output.stdout).into_owned(),
        stderr(&output),
    )
}

/// The console lines Chromium logs for the page (`INFO:CONSOLE`), errors among them.
fn console_lines(log: &str) -> Vec<&str> {
    log.lines().filter(|l| l.contains(":CONSOLE")).collect()
}

#[test]
fn chromium_opens_the_html_plot_and_sees_every_series_without_a_console_error() {
    let dir = scratch();
    trace_plot(&dir, "trace.html");
    let (dom, log) = chromium(&dir, &dir.join("trace.html"));
    assert!(
        console_lines(&log).is_empty(),
        "console: {:?}",
        console_lines(&log)
    );
    assert!(
        dom.contains(r#"data-plot-ready="3""#),
        "the script ran to its end over 3 series: {dom}"
    );
    assert!(!dom.contains("data-plot-error="), "{dom}");
    for series in ["controlword", "modes_of_operation", "target_position"] {
        assert!(
            dom.contains(&format!(
                r#"<path class="series" data-parameter="{series}""#
            )),
            "{series} in the DOM"
        );
    }

    // Zoom: the page with a script of the test's own after ours that turns the wheel over the
    // middle of the drawing (zoom in), then double clicks (everything again).
    let page = std::fs::read_to_string(dir.join("trace.html")).unwrap();
    let probe = r#"<script>
const root = document.querySelector("svg.drivegen-plot");
const plot = () => document.querySelector("svg.plot").getAttribute("viewBox");
const box = root.getBoundingClientRect();
const at = { clientX: box.left + box.width / 2, clientY: box.top + 50, bubbles: true, cancelable: true };
root.dispatchEvent(new WheelEvent("wheel", Object.assign({ deltaY: -100 }, at)));
document.documentElement.setAttribute("data-zoomed", plot());
root.dispatchEvent(new MouseEvent("dblclick", at));
document.documentElement.setAttribute("data-reset", plot());
</script>
</body>"#;
    let zoom = dir.join("zoom.html");
    std::fs::write(&zoom, page.replace("</body>", probe)).unwrap();
    let (dom, log) = chromium(&dir, &zoom);
    assert!(
        console_lines(&log).is_empty(),
        "console: {:?}",
        console_lines(&log)
    );
    let attribute = |name: &str| {
        let start = dom
            .find(&format!("{name}=\""))
            .unwrap_or_else(|| panic!("{name}: {dom}"));
        let rest = &dom[start + name.len() + 2..];
        rest[..rest.find('"').unwrap()].to_owned()
    };
    let width = |view: &str| view.split(' ').nth(2).unwrap().parse::<f64>().unwrap();
    let (zoomed, reset) = (attribute("data-zoomed"), attribute("data-reset"));
    assert!(
        (width(&zoomed) - 0.008).abs() < 1e-9,
        "the wheel zooms in to 80%: {zoomed}"
    );
    assert!(
        (width(&reset) - 0.01).abs() < 1e-9,
        "double click shows all: {reset}"
    );

    // The check can fail: a page whose script throws is seen.
    let broken = dir.join("broken.html");
    std::fs::write(
        &broken,
        "<html><body><script>notDefined()</script></body></html>",
    )
    .unwrap();
    let (_, log) = chromium(&dir, &broken);
    assert!(
        console_lines(&log).iter().any(|l| l.contains("Uncaught")),
        "{log}"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_watch_plot_has_a_panel_per_parameter_asked_for_in_its_unit() {
    let dir = scratch();
    let swd = Path::new(env!("CARGO_MANIFEST_DIR")).join("../descriptions/ezwheel-swd");
    let swd = swd.to_str().unwrap();
    let can = format!(
        "candump:exec:{} sim {swd} --can candump:stdio --node-id 4",
        support::BIN
    );
    let plot = dir.join("watch.svg");
    let output = drivegen(&[
        "watch",
        swd,
        "statusword",
        "position_actual_value",
        "--can",
        &can,
        "--node-id",
        "4",
        "--timeout-ms",
        "10000",
        "--interval-ms",
        "50",
        "--count",
        "3",
        "--plot",
        plot.to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let svg = std::fs::read_to_string(&plot).unwrap();
    let panels: Vec<&str> = svg
        .lines()
        .filter(|l| l.starts_with(r#"<g class="panel""#))
        .collect();
    assert_eq!(
        panels,
        [
            r#"<g class="panel" data-parameter="statusword">"#,
            r#"<g class="panel" data-parameter="position_actual_value">"#
        ]
    );
    assert!(svg.contains(">position_actual_value (inc)</text>"), "{svg}");
    let lines = svg.matches(r#"<path class="series""#).count();
    assert_eq!(lines, 2, "{svg}");
    // Three polls: a start and two more points.
    let path = svg
        .lines()
        .find(|l| l.contains(r#"<path class="series" data-parameter="position_actual_value""#))
        .unwrap();
    assert_eq!(path.matches(" L").count(), 2, "{path}");
    std::fs::remove_dir_all(dir).unwrap();
}
