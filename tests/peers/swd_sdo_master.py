"""python canopen 2.4.1 as an independent SDO master of the simulated ez-Wheel SWD.

    swd_sdo_master.py EDS NODE_ID

Loads the EDS drivegen exported from descriptions/ezwheel-swd into a RemoteNode, relays frames
between this process's stdio (candump compact lines, `123#DEADBEEF`) and python-can's virtual bus,
and uploads every readable object of the EDS. Each value must decode with the EDS data type and
equal the EDS DefaultValue where one is given (the simulator starts at the described defaults).
Reports on stderr ("ok: N objects read, M defaults compared" last) and exits 0 on success, 1 on
the first failed check. stdout carries frames only.
"""

import logging
import os
import sys
import time

import can
import canopen

from canopen import objectdictionary as od
from canopen_relay import relay_stdio

READABLE = {"ro", "rw", "rwr", "rww", "const"}

# Objects the drive changes by itself before any master can read them: the statusword's default
# 0000h is "Not ready to switch on", which the drive leaves automatically for "Switch on disabled"
# 0040h (SWD manual lines 2384, 2390-2391). Read and type-checked, not compared with the default.
MOVES_AT_BOOT = {(0x6041, 0)}


def variables(dictionary):
    for obj in dictionary.values():
        if isinstance(obj, (od.ODRecord, od.ODArray)):
            yield from obj.values()
        else:
            yield obj


def check(node):
    node.sdo.RESPONSE_TIMEOUT = 1.0
    read = compared = 0
    for var in variables(node.object_dictionary):
        if var.access_type not in READABLE:
            continue
        data = node.sdo.upload(var.index, var.subindex)
        value = var.decode_raw(data)
        read += 1
        if var.data_type in od.DATA_TYPES and var.data_type not in (od.VISIBLE_STRING, od.OCTET_STRING, od.DOMAIN):
            size = len(var.encode_raw(value))
            assert len(data) == size, f"{var.index:04X}:{var.subindex} {var.name}: {len(data)} bytes, type says {size}"
        if var.default is not None and not var.relative and (var.index, var.subindex) not in MOVES_AT_BOOT:
            assert value == var.default, f"{var.index:04X}:{var.subindex} {var.name}: read {value!r}, EDS default {var.default!r}"
            compared += 1
    return read, compared


def main():
    logging.basicConfig(level=logging.ERROR)
    eds, node_id = sys.argv[1], int(sys.argv[2], 0)
    channel = f"swd-eds-master-{os.getpid()}"
    bus = can.Bus(interface="virtual", channel=channel)
    network = canopen.Network()
    network.connect(interface="virtual", channel=channel)
    try:
        relay_stdio(bus)
        node = canopen.RemoteNode(node_id, eds)
        network.add_node(node)
        time.sleep(0.2)
        read, compared = check(node)
    except (AssertionError, canopen.SdoAbortedError, canopen.SdoCommunicationError) as failed:
        print(f"FAILED: {failed}", file=sys.stderr, flush=True)
        sys.exit(1)
    finally:
        network.disconnect()
        bus.shutdown()
    print(f"ok: {read} objects read, {compared} defaults compared", file=sys.stderr, flush=True)


if __name__ == "__main__":
    main()
