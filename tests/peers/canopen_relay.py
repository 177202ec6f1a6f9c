"""A python-canopen LocalNode on python-can's virtual bus, relayed to stdin/stdout as candump
compact lines (`605#4000100000000000`, `701#R1`), so a separate process can reach it.

    canopen_relay.py EDS NODE_ID[,NODE_ID...]

With several node ids (comma-separated: wrappers such as cia402_relay.py take arguments after
it), every one is a LocalNode of the same EDS on the same bus (a network of
nodes for a master to manage). Beyond LocalNode: each sends a boot-up at start and after an NMT
reset (LocalNode does not), and a write to 0x2000 sends an EMCY of that node with the written
code (register 0x01, manufacturer bytes 01..05). It exits when stdin closes.
"""
import os
import subprocess
import sys
import threading

import can
import canopen


def parse(line):
    can_id, _, payload = line.partition("#")
    if payload[:1] in ("R", "r"):
        dlc = int(payload[1:] or "0", 16)
        return can.Message(arbitration_id=int(can_id, 16), is_extended_id=False,
                           is_remote_frame=True, dlc=dlc)
    return can.Message(arbitration_id=int(can_id, 16), is_extended_id=False,
                       data=bytes.fromhex(payload.replace(".", "")))


def compact(msg):
    if msg.is_remote_frame:
        return f"{msg.arbitration_id:03X}#R{msg.dlc or ''}"
    return f"{msg.arbitration_id:03X}#{bytes(msg.data).hex().upper()}"


def relay_process(process, bus):
    """Copies frames between a child process speaking candump compact lines on its stdio (e.g.
    `drivegen sim ... --can candump:stdio`, started with text pipes) and `bus`, until it ends."""
    def from_process():
        for line in process.stdout:
            line = line.strip()
            if "#" in line:
                bus.send(parse(line))

    def to_process():
        while process.poll() is None:
            msg = bus.recv(0.1)
            if msg is not None:
                process.stdin.write(compact(msg) + "\n")
                process.stdin.flush()

    for target in (from_process, to_process):
        threading.Thread(target=target, daemon=True).start()


def master_of_simulator(binary, sim_args, channel, scenario, prepare=None,
                        errors=(canopen.SdoAbortedError, canopen.SdoCommunicationError)):
    """Runs `scenario(network)` as a master of `binary sim SIM_ARGS --can candump:stdio`, relayed
    to python-can's virtual bus `channel`, and returns its result. `prepare(network)` runs before
    the simulator starts (to subscribe to its first frames). An AssertionError or one of `errors`
    prints "FAILED: ..." and exits 1. The simulator child is stopped by its PID, the buses shut
    down."""
    bus = can.Bus(interface="virtual", channel=channel)
    network = canopen.Network()
    network.connect(interface="virtual", channel=channel)
    if prepare is not None:
        prepare(network)
    sim = subprocess.Popen(
        [binary, "sim", *sim_args, "--can", "candump:stdio"],
        stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True, bufsize=1)
    try:
        relay_process(sim, bus)
        return scenario(network)
    except (AssertionError, *errors) as failed:
        print(f"FAILED: {failed}", flush=True)
        sys.exit(1)
    finally:
        sim.kill()
        sim.wait()
        network.disconnect()
        bus.shutdown()


def master_on_stdio(name, eds, node_id):
    """A python canopen master of the node at the other end of this process's stdio (see
    `relay_stdio`): the virtual bus `name-PID`, the network on it and the node `node_id` with
    the object dictionary `eds`."""
    channel = f"{name}-{os.getpid()}"
    bus = can.Bus(interface="virtual", channel=channel)
    network = canopen.Network()
    network.connect(interface="virtual", channel=channel)
    relay_stdio(bus)
    return bus, network, network.add_node(node_id, eds)


def relay_stdio(bus):
    """Copies frames between this process's stdio (candump compact lines) and `bus`: for a master
    whose node is the process at the other end of its pipes (a test running the simulated node)."""
    def from_stdin():
        for line in sys.stdin:
            line = line.strip()
            if "#" in line:
                bus.send(parse(line))

    def to_stdout():
        while True:
            msg = bus.recv(0.1)
            if msg is not None:
                sys.stdout.write(compact(msg) + "\n")
                sys.stdout.flush()

    for target in (from_stdin, to_stdout):
        threading.Thread(target=target, daemon=True).start()


def main(install=None):
    """Runs the relay; `install(node)` may add behaviour (write callbacks) to each LocalNode."""
    eds, node_ids = sys.argv[1], [int(arg, 0) for arg in sys.argv[2].split(",")]
    channel = f"drivegen-relay-{os.getpid()}"
    # The relay's own bus exists before anything is sent, so it sees the first boot-up.
    relay = can.Bus(interface="virtual", channel=channel)
    network = canopen.Network()
    network.connect(interface="virtual", channel=channel)
    nodes = {}
    for node_id in node_ids:
        node = canopen.LocalNode(node_id, eds)
        network.add_node(node)
        nodes[node_id] = node

    def boot(node):
        node.nmt.send_command(0x81)  # INITIALISING: sends the boot-up message
        node.nmt.send_command(0x80)  # PRE-OPERATIONAL: starts the heartbeat if 0x1017 is set

    def on_nmt(can_id, data, timestamp):
        command, target = data[0], data[1]
        if command in (0x81, 0x82):
            for node_id, node in nodes.items():
                if target in (0, node_id):
                    boot(node)

    def emcy_on_write(node):
        def on_write(index, subindex, od, data, **kwargs):
            if index == 0x2000:
                node.emcy.send(int.from_bytes(data, "little"), 0x01, b"\x01\x02\x03\x04\x05")
        return on_write

    for node in nodes.values():
        node.add_write_callback(emcy_on_write(node))
        if install is not None:
            install(node)
    network.subscribe(0, on_nmt)
    out_lock = threading.Lock()

    def pump_out():
        while True:
            msg = relay.recv(0.1)
            if msg is not None:
                with out_lock:
                    sys.stdout.write(compact(msg) + "\n")
                    sys.stdout.flush()

    threading.Thread(target=pump_out, daemon=True).start()
    for node in nodes.values():
        boot(node)
    for line in sys.stdin:
        line = line.strip()
        if line:
            relay.send(parse(line))
    network.disconnect()
    relay.shutdown()


if __name__ == "__main__":
    main()
