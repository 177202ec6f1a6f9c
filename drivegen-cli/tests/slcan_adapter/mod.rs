//! A serial SLCAN adapter emulator, written to the Lawicel / CANable command set independently of
//! drivebus's SLCAN code: it serves the adapter end of a pty and bridges its CAN side to
//! `drivegen sim --can candump:stdio` (candump lines on the simulator's stdio), or to a second
//! emulated adapter on the same emulated bus ([`pair`]).
//!
//! Commands: `C` close, `Sn` bit rate (0-8, channel closed), `O` open (bit rate set, channel
//! closed), `Z0`/`Z1` timestamps (channel closed), `V`, `N`, `F` (open), frames `tIIIL..`,
//! `rIIIL`, `TIIIIIIIIL..`, `RIIIIIIIIL` (open; answered `z` / `Z`). Anything else, or a command
//! in the wrong state, is answered with BEL, as the adapters do.

use std::fs::{File, OpenOptions};
use std::io::{BufRead, BufReader, Read, Write};
use std::path::Path;
use std::process::{Command, Stdio};
use std::sync::mpsc::{channel, Receiver, Sender};
use std::sync::{Arc, Mutex};
use std::time::Instant;

use peer_support::Process;

const BEL: u8 = 0x07;

/// How the emulated adapter behaves.
#[derive(Debug, Clone, Copy, Default)]
pub struct Options {
    /// Answers nothing at all (a wrong serial speed, or not an SLCAN adapter).
    pub silent: bool,
    /// Refuses every `Sn` (an adapter that lacks the rate).
    pub refuse_bitrate: bool,
    /// Stamps every received frame, as some CANable firmwares do without `Z1`.
    pub always_timestamp: bool,
    /// Writes a line of noise before every other frame it passes on.
    pub garbage: bool,
}

/// What the adapter saw.
#[derive(Debug, Default)]
pub struct State {
    /// Every command line received, in order.
    pub commands: Vec<String>,
    /// Whether the channel is open.
    pub open: bool,
    bitrate: Option<u8>,
    timestamps: bool,
    /// Frames passed from the pty to the bus.
    pub to_bus: usize,
    /// Frames passed from the bus to the pty.
    pub to_pty: usize,
    /// Commands answered with BEL.
    pub refused: usize,
}

/// A running adapter and the simulator behind it; both stop when dropped.
pub struct Adapter {
    /// What the adapter saw so far.
    pub state: Arc<Mutex<State>>,
    _sim: Process,
}

/// Starts the adapter on `pty` (the adapter end) with `drivegen sim ARGS --can candump:stdio`
/// behind it.
pub fn start(bin: &str, pty: &Path, sim_args: &[&str], options: Options) -> Adapter {
    let mut child = Command::new(bin)
        .arg("sim")
        .args(sim_args)
        .args(["--can", "candump:stdio"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let sim_in = child.stdin.take().unwrap();
    let sim_out = child.stdout.take().unwrap();
    let mut sim_err = BufReader::new(child.stderr.take().unwrap());
    let mut line = String::new();
    sim_err.read_line(&mut line).unwrap();
    assert!(
        line.contains("listening on canopen candump:stdio"),
        "{line}"
    );
    Adapter {
        state: bridge(pty, Box::new(sim_in), Box::new(sim_out), options),
        _sim: Process::new(child),
    }
}

/// Two adapters, on `a` and `b`, on one emulated bus: what one passes to the bus the other
/// receives.
pub fn pair(a: &Path, b: &Path, options: Options) -> [Arc<Mutex<State>>; 2] {
    let (a_tx, b_rx) = channel();
    let (b_tx, a_rx) = channel();
    [
        bridge(
            a,
            Box::new(Lines(a_tx)),
            Box::new(Incoming::new(a_rx)),
            options,
        ),
        bridge(
            b,
            Box::new(Lines(b_tx)),
            Box::new(Incoming::new(b_rx)),
            options,
        ),
    ]
}

/// Candump lines written to a channel.
struct Lines(Sender<Vec<u8>>);

impl Write for Lines {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let _ = self.0.send(buf.to_vec());
        Ok(buf.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// Candump lines read from a channel.
struct Incoming {
    rx: Receiver<Vec<u8>>,
    buffer: Vec<u8>,
}

impl Incoming {
    fn new(rx: Receiver<Vec<u8>>) -> Self {
        Self {
            rx,
            buffer: Vec::new(),
        }
    }
}

impl Read for Incoming {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        if self.buffer.is_empty() {
            match self.rx.recv() {
                Ok(bytes) => self.buffer = bytes,
                Err(_) => return Ok(0),
            }
        }
        let n = buf.len().min(self.buffer.len());
        buf[..n].copy_from_slice(&self.buffer[..n]);
        self.buffer.drain(..n);
        Ok(n)
    }
}

/// Serves the adapter end `pty`; frames go to `to_bus` and come from `from_bus` as candump
/// lines.
fn bridge(
    pty: &Path,
    to_bus: Box<dyn Write + Send>,
    from_bus: Box<dyn Read + Send>,
    options: Options,
) -> Arc<Mutex<State>> {
    let port = OpenOptions::new().read(true).write(true).open(pty).unwrap();
    let writer = Arc::new(Mutex::new(port.try_clone().unwrap()));
    let state = Arc::new(Mutex::new(State::default()));
    let epoch = Instant::now();
    {
        let (state, writer) = (Arc::clone(&state), Arc::clone(&writer));
        std::thread::spawn(move || from_pty(port, to_bus, &writer, &state, options));
    }
    {
        let state = Arc::clone(&state);
        std::thread::spawn(move || to_pty(from_bus, &writer, &state, options, epoch));
    }
    state
}

fn hex(bytes: &[u8]) -> bool {
    bytes.iter().all(u8::is_ascii_hexdigit)
}

/// A frame command's shape: identifier digits, then a length digit, then 2 digits a byte (none
/// for remote frames).
fn frame_ok(line: &[u8], id_digits: usize, remote: bool) -> bool {
    let Some(&len) = line.get(1 + id_digits) else {
        return false;
    };
    if !(b'0'..=b'8').contains(&len) || !hex(&line[1..1 + id_digits]) {
        return false;
    }
    let data = &line[2 + id_digits..];
    if remote {
        data.is_empty()
    } else {
        data.len() == 2 * usize::from(len - b'0') && hex(data)
    }
}

/// Handles one command line; the answer to write back.
fn handle(line: &[u8], state: &mut State, sim: &mut dyn Write) -> Vec<u8> {
    let ok = b"\r".to_vec();
    let closed = !state.open;
    match line {
        b"C" if state.open => {
            state.open = false;
            ok
        }
        [b'S', digit] if closed && (b'0'..=b'8').contains(digit) => {
            state.bitrate = Some(digit - b'0');
            ok
        }
        b"O" if closed && state.bitrate.is_some() => {
            state.open = true;
            ok
        }
        b"Z0" | b"Z1" if closed => {
            state.timestamps = line == b"Z1";
            ok
        }
        b"V" => b"V1013\r".to_vec(),
        b"N" => b"NEMU1\r".to_vec(),
        b"F" if state.open => b"F00\r".to_vec(),
        [b't' | b'r', ..] if state.open && frame_ok(line, 3, line[0] == b'r') => {
            // candump form: III#DD.. or III#R[L].
            let id = std::str::from_utf8(&line[1..4]).unwrap();
            let text = if line[0] == b'r' {
                format!("{id}#R{}\n", line[4] as char)
            } else {
                format!("{id}#{}\n", std::str::from_utf8(&line[5..]).unwrap())
            };
            let _ = sim.write_all(text.as_bytes()).and_then(|()| sim.flush());
            state.to_bus += 1;
            b"z\r".to_vec()
        }
        // Extended frames: acknowledged, not passed on (the simulated bus is 11-bit).
        [b'T' | b'R', ..] if state.open && frame_ok(line, 8, line[0] == b'R') => b"Z\r".to_vec(),
        _ => {
            state.refused += 1;
            vec![BEL]
        }
    }
}

fn from_pty(
    mut port: File,
    mut sim: Box<dyn Write + Send>,
    writer: &Mutex<File>,
    state: &Mutex<State>,
    options: Options,
) {
    let mut line = Vec::new();
    let mut chunk = [0u8; 256];
    loop {
        let n = match port.read(&mut chunk) {
            Ok(0) | Err(_) => return,
            Ok(n) => n,
        };
        for &byte in &chunk[..n] {
            if byte != b'\r' {
                line.push(byte);
                continue;
            }
            let mut state = state.lock().unwrap();
            state
                .commands
                .push(String::from_utf8_lossy(&line).into_owned());
            if !options.silent {
                let answer = if options.refuse_bitrate && line.first() == Some(&b'S') {
                    state.refused += 1;
                    vec![BEL]
                } else {
                    handle(&line, &mut state, &mut *sim)
                };
                let mut port = writer.lock().unwrap();
                let _ = port.write_all(&answer).and_then(|()| port.flush());
            }
            line.clear();
        }
    }
}

fn to_pty(
    sim: impl Read,
    writer: &Mutex<File>,
    state: &Mutex<State>,
    options: Options,
    epoch: Instant,
) {
    for line in BufReader::new(sim).lines() {
        let Ok(line) = line else { return };
        // The last word with a '#' is the frame (a bare `III#DD..` from the simulator).
        let Some(frame) = line.split_whitespace().rfind(|w| w.contains('#')) else {
            continue;
        };
        let (id, payload) = frame.split_once('#').unwrap();
        let mut out = if let Some(len) = payload.strip_prefix('R') {
            format!("r{id}{}", if len.is_empty() { "0" } else { len })
        } else {
            format!("t{id}{}{payload}", payload.len() / 2)
        };
        let mut state = state.lock().unwrap();
        if options.silent || !state.open {
            continue;
        }
        if state.timestamps || options.always_timestamp {
            let millis = epoch.elapsed().as_millis() % 60_000;
            out.push_str(&format!("{millis:04X}"));
        }
        out.push('\r');
        let mut bytes = Vec::new();
        if options.garbage && state.to_pty % 2 == 0 {
            bytes.extend_from_slice(b"\x55\xAA!noise t12\x00q\r");
        }
        bytes.extend_from_slice(out.as_bytes());
        state.to_pty += 1;
        let mut port = writer.lock().unwrap();
        let _ = port.write_all(&bytes).and_then(|()| port.flush());
    }
}
