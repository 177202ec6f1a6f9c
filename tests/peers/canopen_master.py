"""python canopen 2.4.1 as the CANopen master of the drivegen simulator.

    canopen_master.py DRIVEGEN_BINARY DESCRIPTION NODE_ID

Builds its object dictionary from `drivegen dump --json` (the IR), starts
`drivegen sim DESCRIPTION --can candump:stdio` as a child, and relays frames between the child's
stdio (candump compact lines) and python-can's virtual bus. Then, as RemoteNode / BaseNode402:
SDO reads and writes, the simulator's abort codes, NMT, and the CiA 402 state machine to
OPERATION ENABLED and back. Prints "ok" and exits 0 on success; prints the failed check and
exits 1 otherwise. The simulator child is stopped by its PID on exit.
"""

import json
import logging
import os
import subprocess
import sys
import time

import canopen
from canopen import objectdictionary as od
from canopen.sdo.exceptions import SdoAbortedError

from canopen_relay import master_of_simulator

TYPES = {
    "bool": od.BOOLEAN, "u8": od.UNSIGNED8, "u16": od.UNSIGNED16, "u24": od.UNSIGNED24,
    "u32": od.UNSIGNED32, "u40": od.UNSIGNED40, "u48": od.UNSIGNED48, "u56": od.UNSIGNED56,
    "u64": od.UNSIGNED64, "i8": od.INTEGER8, "i16": od.INTEGER16, "i24": od.INTEGER24,
    "i32": od.INTEGER32, "i40": od.INTEGER40, "i48": od.INTEGER48, "i56": od.INTEGER56,
    "i64": od.INTEGER64, "f32": od.REAL32, "f64": od.REAL64, "string": od.VISIBLE_STRING,
    "octets": od.OCTET_STRING,
}


def dictionary(ir):
    """The IR's CANopen objects as a python-canopen ObjectDictionary."""
    by_index = {}
    for parameter in ir["parameters"]:
        for address in parameter["canopen"]:
            by_index.setdefault(address["index"], []).append((parameter, address))
    result = od.ObjectDictionary()
    for index, members in sorted(by_index.items()):
        def variable(parameter, address):
            var = od.ODVariable(parameter["name"], index, address["subindex"])
            var.data_type = TYPES[parameter["type"]]
            access = address["access"]
            var.access_type = {(True, True): "rw", (True, False): "ro", (False, True): "wo"}[
                (access["read"], access["write"])]
            return var
        if len(members) == 1 and members[0][1]["subindex"] == 0:
            result.add_object(variable(*members[0]))
        else:
            record = od.ODRecord(f"object_{index:04x}", index)
            for parameter, address in members:
                record.add_member(variable(parameter, address))
            result.add_object(record)
    return result


def abort_code(action):
    try:
        action()
    except SdoAbortedError as e:
        return e.code
    raise AssertionError("expected an SDO abort")


def scenario(node):
    node.sdo.RESPONSE_TIMEOUT = 1.0
    status = node.sdo["statusword"].raw
    assert status & 0x4F == 0x40, f"switch on disabled after boot, statusword {status:#06x}"

    assert abort_code(lambda: node.sdo.download(0x6041, 0, b"\x00\x00")) == 0x06010002, "read-only"
    assert abort_code(lambda: node.sdo.upload(0x2FFF, 0)) == 0x06020000, "no object"
    assert abort_code(lambda: node.sdo.upload(0x6040, 9)) == 0x06090011, "no subindex"

    node.sdo["modes_of_operation"].raw = 3  # profile velocity
    shown = node.sdo["modes_of_operation_display"].raw
    assert shown == 3, f"mode display follows the mode, got {shown}"

    node.nmt.state = "OPERATIONAL"
    node.setup_402_state_machine(read_pdos=False)
    node.state = "OPERATION ENABLED"
    assert node.state == "OPERATION ENABLED", f"state {node.state}"
    node.sdo["target_velocity"].raw = 500
    first = node.sdo["velocity_actual_value"].raw
    deadline = time.monotonic() + 5
    actual = first
    while actual != 500 and time.monotonic() < deadline:
        time.sleep(0.05)
        actual = node.sdo["velocity_actual_value"].raw
    assert actual == 500, f"velocity actual value {actual} (first {first})"
    node.state = "SWITCH ON DISABLED"
    assert node.state == "SWITCH ON DISABLED", f"state {node.state}"
    actual = node.sdo["velocity_actual_value"].raw
    assert actual == 0, f"disabled drive stands still, got {actual}"


def main():
    logging.basicConfig(level=logging.ERROR)  # python canopen warns on every SDO statusword read
    binary, description, node_id = sys.argv[1], sys.argv[2], int(sys.argv[3], 0)
    ir = json.loads(subprocess.check_output([binary, "dump", description, "--json"]))

    def run(network):
        node = canopen.BaseNode402(node_id, dictionary(ir))
        network.add_node(node)
        time.sleep(0.2)
        scenario(node)

    sim_args = [description, "--node-id", str(node_id)]
    master_of_simulator(binary, sim_args, f"drivegen-master-{os.getpid()}", run, errors=())
    print("ok", flush=True)


if __name__ == "__main__":
    main()
