"""Loads an EDS exported by drivegen with python canopen's import_od and compares it with the IR.

Usage: eds_import_check.py FILE.eds IR.json NODE_ID

Exit status 0 when the file loads without any warning and python canopen sees exactly the CANopen
objects of the IR (`drivegen dump --json`): same indices and sub-indices, data types, access types,
PDO mappability, defaults (node-relative ones resolved with NODE_ID) and limits. The IR's declared
PDOs must appear as their communication and mapping objects (CiA 301 7.5.2.35-38), derived here
from the IR's `pdos` independently of drivegen, unless the description defines those objects
itself. Every difference is printed on stderr.
"""

import json
import logging
import sys
import warnings

import canopen
from canopen.objectdictionary import ODArray, ODRecord

TYPE_CODES = {
    "bool": 0x01, "i8": 0x02, "i16": 0x03, "i32": 0x04, "u8": 0x05, "u16": 0x06, "u32": 0x07,
    "f32": 0x08, "string": 0x09, "octets": 0x0A, "i24": 0x10, "f64": 0x11, "i40": 0x12,
    "i48": 0x13, "i56": 0x14, "i64": 0x15, "u24": 0x16, "u40": 0x18, "u48": 0x19, "u56": 0x1A,
    "u64": 0x1B,
}
# python canopen 2.4.1 parses limits only for these signed widths (_calc_bit_length) and for
# unsigned types; it silently drops the limits of float and odd-width signed objects.
LIMITS_PARSED = {"i8", "i16", "i32", "i64", "u8", "u16", "u24", "u32", "u40", "u48", "u56", "u64", "bool"}


class Collect(logging.Handler):
    def __init__(self):
        super().__init__(logging.WARNING)
        self.records = []

    def emit(self, record):
        self.records.append(self.format(record))


def access_type(address):
    if address["constant"]:
        return "const"
    read, write = address["access"]["read"], address["access"]["write"]
    if read and write:
        return {"tx": "rwr", "rx": "rww"}.get(address["pdo"], "rw")
    return "wo" if write else "ro"


def expected_objects(ir, node_id):
    """(index, subindex) -> the fields python canopen should report, default variant only."""
    default_variant = ir["variants"][0]["name"] if ir["variants"] else None
    out = {}
    for p in ir["parameters"]:
        if p["variants"] and default_variant not in p["variants"]:
            continue
        for a in p["canopen"]:
            if a["variant"] not in (None, default_variant):
                continue
            key = (a["index"], a["subindex"])
            if key in out:
                continue
            default = p["default"]
            if default is not None and p["default_plus_node_id"]:
                default += node_id
            if p["type"] in ("string", "octets"):
                default = None
            limits = p["range"] if p["type"] in LIMITS_PARSED else None
            out[key] = {
                "data_type": TYPE_CODES[p["type"]],
                "access_type": access_type(a),
                "pdo_mappable": a["pdo"] != "none",
                "default": default,
                "min": limits["min"] if limits else None,
                "max": limits["max"] if limits else None,
            }
    return out


def pdo_bits(type_name):
    """Bits a value of this IR type takes in a PDO."""
    return 1 if type_name == "bool" else int(type_name[1:])


def pdo_objects(ir, taken, node_id):
    """(index, subindex) -> expected fields of the objects the IR's PDOs imply."""
    by_name = {p["name"]: p for p in ir["parameters"]}
    out = {}

    def var(index, sub, data_type, access, default):
        out[(index, sub)] = {
            "data_type": data_type, "access_type": access, "pdo_mappable": False,
            "default": default, "min": None, "max": None,
        }

    for pdo in ir.get("pdos", []):
        offset = pdo["number"] - 1
        rx = pdo["direction"] == "rx"
        communication = (0x1400 if rx else 0x1800) + offset
        mapping = (0x1600 if rx else 0x1A00) + offset
        if communication not in taken:
            given = pdo["cob_id"]
            if given is None:
                cob_id = 0x80000000  # disabled, no identifier given
            else:
                cob_id = given["value"] + (node_id if given["plus_node_id"] else 0)
                cob_id |= 0 if pdo["enabled"] else 0x80000000
            kind = pdo["transmission_type"]
            highest = 5 if pdo["event_timer"] is not None else 3 if pdo["inhibit_time"] is not None else 1 if kind is None else 2
            var(communication, 0, 0x05, "ro", highest)
            var(communication, 1, 0x07, "rw", cob_id)
            if kind is not None:
                var(communication, 2, 0x05, "rw", kind)
            for sub, key in ((3, "inhibit_time"), (5, "event_timer")):
                if pdo[key] is not None:
                    var(communication, sub, 0x06, "rw", pdo[key])
        if mapping not in taken:
            var(mapping, 0, 0x05, "rw", len(pdo["entries"]))
            for sub, name in enumerate(pdo["entries"], start=1):
                p = by_name[name]
                a = next(a for a in p["canopen"] if a["variant"] is None)
                value = a["index"] << 16 | a["subindex"] << 8 | pdo_bits(p["type"])
                var(mapping, sub, 0x07, "rw", value)
    return out


def actual_objects(od):
    out = {}
    for obj in od.values():
        members = obj.values() if isinstance(obj, (ODRecord, ODArray)) else [obj]
        for var in members:
            out[(var.index, var.subindex)] = {
                "data_type": var.data_type,
                "access_type": var.access_type,
                "pdo_mappable": var.pdo_mappable,
                "default": var.default,
                "min": var.min,
                "max": var.max,
            }
    return out


def main():
    eds, ir_path, node_id = sys.argv[1], sys.argv[2], int(sys.argv[3])
    collect = Collect()
    logging.getLogger().addHandler(collect)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        od = canopen.objectdictionary.import_od(eds, node_id)
    problems = [f"warning: {r}" for r in collect.records]
    problems += [f"python warning: {w.message}" for w in caught]
    with open(ir_path) as f:
        ir = json.load(f)
    expected = expected_objects(ir, node_id)
    taken = {index for index, _ in expected} | {r["index"] for r in ir["records"]}
    expected.update(pdo_objects(ir, taken, node_id))
    actual = actual_objects(od)
    for key in sorted(set(expected) | set(actual)):
        where = f"0x{key[0]:04X} sub {key[1]}"
        if key not in actual:
            problems.append(f"{where}: in the IR, not in the EDS")
        elif key not in expected:
            problems.append(f"{where}: in the EDS, not in the IR")
        else:
            for field, want in expected[key].items():
                got = actual[key][field]
                if got != want:
                    problems.append(f"{where}: {field} is {got!r}, the IR says {want!r}")
    for p in problems:
        print(p, file=sys.stderr)
    print(f"{len(actual)} objects compared")
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
