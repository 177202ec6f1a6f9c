"""python canopen 2.4.1 boots a simulated drive as a CANopen master would, through the EDS
drivegen exported for it.

    eds_boot_master.py DRIVEGEN_BINARY DESCRIPTION EDS NODE_ID

Starts `drivegen sim DESCRIPTION --can candump:stdio --node-id NODE_ID` as a child (relayed to
python-can's virtual bus, stopped by its PID on exit) and loads EDS into a BaseNode402. Then the
CiA 301 / 302 boot-up checks: device type (1000h) and identity (1018h sub 0 and the entries the
EDS lists) are read and compared with the EDS default values where the EDS gives them; the
heartbeat is switched on (1017h where the EDS has it, else the simulator's --heartbeat-ms) and NMT
START must show OPERATIONAL in the node's heartbeat. Where the
EDS has the CiA 402 controlword and statusword (6040h, 6041h), BaseNode402 drives the state
machine to OPERATION ENABLED and back to SWITCH ON DISABLED. Prints "ok: ..." last and exits 0,
or prints the failed check and exits 1.
"""

import logging
import os
import sys
import time

import canopen

from canopen_relay import master_of_simulator


HEARTBEAT_MS = 50


def read_checked(node, index, subindex):
    """Reads an object and compares it with the EDS default, if the EDS gives one."""
    var = node.object_dictionary[index]
    if subindex is not None:
        var = var[subindex]
    value = var.decode_raw(node.sdo.upload(index, subindex or 0))
    if var.default is not None and not var.relative:
        assert value == var.default, (
            f"{index:04X}:{subindex or 0} reads {value:#x}, EDS default {var.default:#x}")
    return value


def identity(node):
    """1000h and the 1018h entries the EDS lists: what a master reads first."""
    device_type = read_checked(node, 0x1000, None)
    record = node.object_dictionary[0x1018]
    entries = record[0].default or 0
    assert entries >= 1, "1018h lists at least the vendor-ID"
    found = {"device type": device_type}
    for sub, name in ((1, "vendor-ID"), (2, "product code"), (3, "revision"), (4, "serial")):
        if sub <= entries and sub in record:
            found[name] = read_checked(node, 0x1018, sub)
    return found


def boot(node):
    """Heartbeat on, NMT START, and the node's own heartbeat must say OPERATIONAL."""
    if 0x1017 in node.object_dictionary:
        node.sdo[0x1017].raw = HEARTBEAT_MS
    node.nmt.send_command(0x01)  # START remote node
    deadline = time.monotonic() + 3
    state = None
    while time.monotonic() < deadline and state != "OPERATIONAL":
        state = node.nmt.wait_for_heartbeat(timeout=1)
    assert state == "OPERATIONAL", f"heartbeat reports {state} after NMT START"


def drive_402(node):
    """The CiA 402 state machine, where the description has it."""
    if 0x6040 not in node.object_dictionary or 0x6041 not in node.object_dictionary:
        return "no CiA 402"
    node.setup_402_state_machine(read_pdos=False)
    visited = []
    for target in ("READY TO SWITCH ON", "SWITCHED ON", "OPERATION ENABLED", "SWITCH ON DISABLED"):
        node.state = target
        assert node.state == target, f"asked for {target}, statusword says {node.state}"
        visited.append(target)
    return " -> ".join(visited)


def main():
    logging.basicConfig(level=logging.ERROR)  # python canopen warns on every SDO statusword read
    binary, description, eds, node_id = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4], 0)

    def run(network):
        node = canopen.BaseNode402(node_id, eds)
        network.add_node(node)
        node.sdo.RESPONSE_TIMEOUT = 2.0
        time.sleep(0.2)
        found = identity(node)
        boot(node)
        return found, drive_402(node)

    sim_args = [description, "--node-id", str(node_id), "--heartbeat-ms", str(HEARTBEAT_MS)]
    found, states = master_of_simulator(binary, sim_args, f"drivegen-boot-{os.getpid()}", run)
    shown = ", ".join(f"{name} {value:#010x}" for name, value in found.items())
    print(f"ok: {shown}; NMT OPERATIONAL; {states}", flush=True)


if __name__ == "__main__":
    main()
