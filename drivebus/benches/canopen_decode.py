"""Decodes a candump log with python-can + python-canopen, the way a Python master would, and
prints the rate as JSON. Run by `cargo bench --bench canopen` on the log that bench generates.

    canopen_decode.py LOG EDS [MAX_FRAMES]

The frames are read with python-can's CanutilsLogReader and decoded into typed values with
python-canopen objects: TPDO1 through a PdoMap (statusword-like u16, i32, u8), expedited SDO
upload responses through the object dictionary's decode_raw, heartbeats through NmtMaster and
EMCY through EmcyConsumer.
"""
import json
import struct
import sys
import time

import can
import canopen


def main():
    path, eds = sys.argv[1], sys.argv[2]
    limit = int(sys.argv[3]) if len(sys.argv) > 3 else None
    network = canopen.Network()  # never connected: frames come from the log
    node = canopen.RemoteNode(5, eds)
    network.add_node(node)
    tpdo = node.tpdo[1]
    tpdo.clear()
    for index in (0x2002, 0x2004, 0x2001):
        tpdo.add_variable(index)
    tpdo.cob_id = 0x185  # as configured on the node
    od = node.object_dictionary

    frames = 0
    checksum = 0
    start = time.perf_counter()
    for msg in can.CanutilsLogReader(path):
        can_id, data = msg.arbitration_id, msg.data
        if can_id == 0x185:
            tpdo.on_message(can_id, data, msg.timestamp)
            checksum += sum(var.raw for var in tpdo.map)
        elif can_id == 0x585:
            command, index, subindex = struct.unpack_from("<BHB", data)
            if command & 0x02:  # expedited
                size = 4 - ((command >> 2) & 0x3) if command & 0x01 else 4
                checksum += od[index].decode_raw(bytes(data[4:4 + size]))
        elif can_id == 0x705:
            node.nmt.on_heartbeat(can_id, data, msg.timestamp)
            checksum += node.nmt._state
        elif can_id == 0x085:
            node.emcy.on_emcy(can_id, data, msg.timestamp)
            checksum += node.emcy.log[-1].code
            node.emcy.log.clear()
        frames += 1
        if limit is not None and frames >= limit:
            break
    elapsed = time.perf_counter() - start
    print(json.dumps({"frames": frames, "seconds": elapsed, "frames_per_second": frames / elapsed,
                      "checksum": checksum}))


if __name__ == "__main__":
    main()
