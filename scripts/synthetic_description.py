#!/usr/bin/env python3
"""Writes a synthetic description with N parameters (default 2000) for the compile-time budget.

The mix resembles real drives: plain registers, scaled values with units, enums and flags shared
by many parameters, 32-bit pairs, and a CANopen address on every fourth parameter.
"""
import sys

def main() -> None:
    count = int(sys.argv[1]) if len(sys.argv) > 1 else 2000
    out = [
        "format = 1",
        "[device]",
        'name = "Synthetic"',
        'handle = "Synthetic"',
        "[[source]]",
        'id = "gen"',
        'file = "scripts/synthetic_description.py"',
        'title = "Generated for the compile-time budget"',
    ]
    for e in range(20):
        out += [
            "[[enum]]", f'name = "mode_{e}"', 'type = "u16"', 'source = { doc = "gen", line = 1 }',
            "values = [" + ", ".join(f'{{ name = "value_{v}", value = {v} }}' for v in range(8)) + "]",
        ]
    for f in range(20):
        out += [
            "[[flags]]", f'name = "status_{f}"', 'type = "u16"', 'source = { doc = "gen", line = 1 }',
            "bits = [" + ", ".join(f'{{ name = "bit_{b}", bit = {b} }}' for b in range(12)) + "]",
        ]
    address = 0
    for i in range(count):
        kind = i % 5
        lines = ["[[parameter]]", f'name = "parameter_{i}"', f'doc = "Synthetic parameter {i}."']
        words = 1
        if kind == 0:
            lines += ['type = "u16"', "range = [0, 1000]"]
        elif kind == 1:
            lines += ['type = "i16"', 'unit = "rpm"', 'scale = "1/10"']
        elif kind == 2:
            lines += ['type = "u16"', f'enum = "mode_{i % 20}"']
        elif kind == 3:
            lines += ['type = "u16"', f'flags = "status_{i % 20}"']
        else:
            lines += ['type = "i32"', 'unit = "inc"']
            words = 2
        lines.append(f'modbus = {{ table = "holding", address = {address}, words = {words} }}')
        if i % 4 == 0:
            lines.append(f'canopen = {{ index = {0x2000 + i // 4}, subindex = 0, access = "rw" }}')
        lines.append('source = { doc = "gen", line = 1 }')
        out += lines
        address += words
    print("\n".join(out))

if __name__ == "__main__":
    main()
