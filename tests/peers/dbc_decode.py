"""Decodes a candump capture with cantools through a DBC file, as an independent second party
to `drivegen decode` (drivegen-cli/tests/dbc.rs).

Usage: dbc_decode.py FILE.dbc CAPTURE.log
Prints one JSON object per frame: {"id": .., "message": .., "signals": {name: value}}, a value
being a number, or the value table's name for an enumerated one; {"id": .., "unknown": true}
for a frame the DBC has no message for.
"""
import json
import sys

import cantools


def frames(path):
    with open(path) as capture:
        for line in capture:
            fields = line.split()
            if len(fields) < 3 or "#" not in fields[2]:
                continue
            can_id, data = fields[2].split("#", 1)
            yield int(can_id, 16), bytes.fromhex(data)


def main():
    database = cantools.database.load_file(sys.argv[1], strict=True)
    for can_id, data in frames(sys.argv[2]):
        try:
            message = database.get_message_by_frame_id(can_id)
        except KeyError:
            print(json.dumps({"id": can_id, "unknown": True}))
            continue
        decoded = message.decode(data, decode_choices=True)
        signals = {
            name: value.name if hasattr(value, "name") else value
            for name, value in decoded.items()
        }
        print(json.dumps({"id": can_id, "message": message.name, "signals": signals}))


if __name__ == "__main__":
    main()
