#!/usr/bin/env python3
"""A candump log for `drivegen trace` and `decode` (issue 33, scripts/bench-trace).

Usage: trace-log.py IR.json FRAMES SEED OUT [--noise]

IR.json is `drivegen dump --json` of the description the log is traced with. Every 16 frames:
six PDOs (TPDO 1-4, RPDO 1; declared mappings, one learned from the SDO writes at the start,
one learned with a gap, and unmapped ones), expedited SDO upload responses and download requests
of random objects of the description with random values, their answers, an upload request, a
heartbeat, an EMCY, a SYNC, an NMT command, and one of an SDO abort, a segment, a TIME frame, a
remote frame or another identifier. Nodes 1 and 2. --noise adds compact lines (no timestamp),
comments, blank lines and malformed lines (which `decode` refuses).
"""
import json
import random
import sys

ir_path, frames, seed, out = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
noise = "--noise" in sys.argv
ir = json.load(open(ir_path))
rng = random.Random(seed)
objects = [
    (a["index"], a["subindex"])
    for p in ir["parameters"]
    for a in p["canopen"]
] or [(0x2000 + i, i % 3) for i in range(40)]
by_name = {p["name"]: (p["canopen"][0]["index"], p["canopen"][0]["subindex"])
           for p in ir["parameters"] if p["canopen"]}
statusword = by_name.get("statusword", (0x6041, 0))
position = by_name.get("position_actual_value", (0x6064, 0))
ABORTS = [0x06020000, 0x06090011, 0x08000022, 0x05040001, 0x12345678]
EMCY = [0x0000, 0x2310, 0x3210, 0x5530, 0x8611, 0xFF00, 0x1234]


def mapping(index, sub, bits):
    return (index << 16) | (sub << 8) | bits


def sdo(cob, command, obj, value=b""):
    index, sub = obj
    data = bytes([command, index & 0xFF, index >> 8, sub]) + value
    return cob, data + bytes(8 - len(data))



lines = []
t = 1700000000.0


def emit(cob, data, remote=False):
    global t
    t += 0.0001
    payload = "R" if remote else data.hex().upper()
    if noise and rng.random() < 0.05:
        lines.append(f"{cob:03X}#{payload}")
    else:
        lines.append(f"({t:.6f}) can0 {cob:03X}#{payload}")


# TPDO 2 of node 1 learned: statusword and position; TPDO 4 with a gap (sub-index 2 only).
for sub, value in [(0, 0), (1, mapping(*statusword, 16)), (2, mapping(*position, 32)), (0, 2)]:
    emit(*sdo(0x601, 0x23, (0x1A01, sub), value.to_bytes(4, "little")))
emit(*sdo(0x601, 0x23, (0x1A03, 2), mapping(*statusword, 16).to_bytes(4, "little")))
while len(lines) < frames:
    node = 1 if rng.random() < 0.8 else 2
    k = len(lines) % 16
    if k < 6:
        cob = [0x180, 0x280, 0x380, 0x480, 0x200, 0x180][k] + node
        emit(cob, rng.randbytes(rng.choice([8, 8, 8, 6, 2])))
    elif k in (6, 7):
        n = rng.randint(1, 4)
        base = 0x43 if k == 6 else 0x23
        obj = rng.choice(objects)
        emit(*sdo((0x580 if k == 6 else 0x600) + node, base | ((4 - n) << 2), obj, rng.randbytes(n)))
    elif k == 8:
        emit(*sdo(0x580 + node, 0x60, rng.choice(objects)))
    elif k == 9:
        emit(*sdo(0x600 + node, 0x40, rng.choice(objects)))
    elif k == 10:
        emit(0x700 + node, bytes([rng.choice([0x00, 0x04, 0x05, 0x7F])]))
    elif k == 11:
        code = rng.choice(EMCY)
        emit(0x080 + node, code.to_bytes(2, "little") + bytes([rng.randint(0, 255)]) + bytes(5))
    elif k == 12:
        emit(0x080, b"" if rng.random() < 0.5 else bytes([rng.randint(1, 240)]))
    elif k == 13:
        emit(0x000, bytes([rng.choice([0x01, 0x02, 0x80, 0x81, 0x82]), rng.choice([0, node])]))
    elif k == 14:
        choice = rng.randint(0, 5)
        if choice == 0:
            code = rng.choice(ABORTS).to_bytes(4, "little")
            emit(*sdo(rng.choice([0x580, 0x600]) + node, 0x80, rng.choice(objects), code))
        elif choice == 1:
            emit(rng.choice([0x580, 0x600]) + node, rng.randbytes(8))
        elif choice == 2:
            emit(0x100, rng.randbytes(6))
        elif choice == 3:
            emit(0x700 + node, b"", remote=True)
        elif choice == 4:
            emit(rng.randint(0, 0x7FF), rng.randbytes(rng.randint(0, 8)))
        else:
            emit(*sdo(0x600 + node, 0x21, rng.choice(objects), (20).to_bytes(4, "little")))
    else:
        emit(0x181 if node == 1 else 0x182, rng.randbytes(8))
    if noise and rng.random() < 0.002:
        lines.append(rng.choice(["", "# a comment", "not a frame", "123#0", "(1.5) can0 12#00"]))
with open(out, "w") as f:
    f.write("\n".join(lines) + "\n")
