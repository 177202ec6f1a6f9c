#!/usr/bin/env python3
"""Writes the seed corpora of the fuzz targets (fuzz/seeds/<target>/) from the project's test
vectors and the manuals' frames. Run from anywhere: `python3 fuzz/seeds/make.py`. Each target's
input layout is documented at the top of fuzz/fuzz_targets/<target>.rs; the seeds follow it.
"""
import pathlib
import struct

FUZZ = pathlib.Path(__file__).resolve().parent.parent
ROOT = FUZZ.parent
SEEDS = FUZZ / "seeds"


def crc16_modbus(data):
    crc = 0xFFFF
    for b in data:
        crc ^= b
        for _ in range(8):
            crc = (crc >> 1) ^ 0xA001 if crc & 1 else crc >> 1
    return struct.pack("<H", crc)


def write(target, name, data):
    folder = SEEDS / target
    folder.mkdir(parents=True, exist_ok=True)
    (folder / name).write_bytes(bytes(data))


# Not seeds: an include of /dev/zero, read up to the 8 MiB bound on every mutation of it.
SLOW_SEEDS = {"files_are_small.toml"}


def copy_files(target, pattern_dirs):
    for folder, pattern in pattern_dirs:
        for path in sorted((ROOT / folder).glob(pattern)):
            if path.name not in SLOW_SEEDS:
                write(target, path.name, path.read_bytes())


# Lafert Modbus manual (001_ad8624675505a5b5.txt) lines 157-233: request PDUs after the address.
LAFERT_REQUESTS = {
    "line158_write_address": "06 00 28 00 02",
    "line163_save_eeprom": "06 00 00 00 01",
    "line168_reset": "06 A5 A5 00 01",
    "line177_baud": "06 00 35 00 60",
    "line198_com_setting": "06 00 2B 00 01",
    "line219_read_status": "04 00 60 00 01",
    "line226_read_17": "04 00 2B 00 17",
    "line232_read_com": "03 00 2B 00 01",
    "line240_read_6": "03 00 3C 00 06",
}


def hexbytes(text):
    return [int(b, 16) for b in text.split()]


def request_bytes(pdu):
    """The 5-byte request layout of fuzz/src/modbus_request.rs for a read or single write PDU."""
    kinds = {0x01: 0, 0x02: 1, 0x03: 2, 0x04: 3, 0x05: 4, 0x06: 5, 0x0F: 6, 0x10: 7}
    return [kinds[pdu[0]]] + pdu[1:5]


def answer_pdu(pdu):
    """A normal answer to a request PDU: registers counting up, or the write's echo."""
    function, count = pdu[0], (pdu[3] << 8) | pdu[4]
    if function in (0x03, 0x04):
        data = [i & 0xFF for i in range(2 * count)]
        return [function, 2 * count] + data
    return pdu[:5]


def modbus_seeds():
    for name, text in LAFERT_REQUESTS.items():
        pdu = hexbytes(text)
        write("modbus_server_request", name, [0] + pdu)
        answer = answer_pdu(pdu)
        rtu = [1] + answer
        rtu += list(crc16_modbus(rtu))
        # Garbage, an exception from the unit, then the answer.
        exception = [1, pdu[0] | 0x80, 2]
        exception += list(crc16_modbus(exception))
        write("modbus_rtu_scan", name, [1, 4] + request_bytes(pdu) + rtu)
        write("modbus_rtu_scan", name + "_after_garbage", [1, 7] + request_bytes(pdu) + [0xFF, 0x00] + rtu)
        write("modbus_rtu_scan", name + "_exception", [1, 3] + request_bytes(pdu) + exception)
        for tx in (7, 0xFFFF):
            mbap = list(struct.pack(">HHHB", tx, 0, len(answer) + 1, 1)) + answer
            stale = list(struct.pack(">HHHB", (tx - 1) & 0xFFFF, 0, len(answer) + 1, 1)) + answer
            write("modbus_tcp_scan", f"{name}_tx{tx}", [1, 9] + list(struct.pack(">H", tx)) + request_bytes(pdu) + stale + mbap)
    write("modbus_server_request", "write_coils", [0, 0x0F, 0, 1, 0, 10, 2, 0xFF, 0x03])
    write("modbus_server_request", "write_registers", [1, 0x10, 0, 0x28, 0, 2, 4, 0, 1, 0, 2])
    write("modbus_server_request", "read_coils_kinco", [2, 0x01, 0, 0, 0, 8])


def sdo_client_seeds():
    mux = [0x00, 0x20, 0x01]
    expedited = [0x43] + mux + [1, 2, 3, 4]
    write("sdo_client", "upload_expedited", [0, 8, 0] + [1, 0] + expedited)
    segmented = [[0x41] + mux + [10, 0, 0, 0], [0x00] + list(range(7)), [0x13] + [7, 8, 9, 0, 0, 0, 0]]
    write("sdo_client", "upload_segmented", [0, 16, 0] + sum(([1, 0] + f for f in segmented), []))
    write("sdo_client", "download_expedited", [1, 2, 0] + [1, 0] + [0x60] + mux + [0] * 4)
    segs = [[0x60] + mux + [0] * 4, [0x20] + [0] * 7, [0x30] + [0] * 7]
    write("sdo_client", "download_segmented", [1, 10, 0] + sum(([1, 0] + f for f in segs), []))
    write("sdo_client", "server_abort", [0, 8, 0] + [1, 0] + [0x80] + mux + [0x00, 0x00, 0x02, 0x06])
    block = [[0xC4] + mux + [5, 0, 0, 0], [0x81, 1, 2, 3, 4, 5, 0, 0], [0xD5, 0, 0, 0, 0, 0, 0, 0]]
    write("sdo_client", "block_upload", [2, 8, 4] + sum(([1, 0] + f for f in block), []))
    block_down = [[0xA4] + mux + [4, 0, 0, 0], [0xA2, 1, 4, 0, 0, 0, 0, 0], [0xA1, 0, 0, 0, 0, 0, 0, 0]]
    write("sdo_client", "block_download", [3, 10, 0] + sum(([1, 0] + f for f in block_down), []))


def sdo_server_seeds():
    frame = lambda data: [0] + data
    write("sdo_server", "upload_expedited", [127] + frame([0x40, 0x00, 0x10, 0, 0, 0, 0, 0]))
    write("sdo_server", "upload_segmented", [127] + frame([0x40, 0x08, 0x10, 0, 0, 0, 0, 0]) + frame([0x60] + [0] * 7) + frame([0x70] + [0] * 7))
    write("sdo_server", "download_expedited", [127] + frame([0x2B, 0x00, 0x20, 1, 0x78, 0x56, 0, 0]))
    write("sdo_server", "download_segmented", [127] + frame([0x21, 0x08, 0x10, 0, 9, 0, 0, 0]) + frame([0x00] + list(b"drivege")) + frame([0x1B, ord("n"), ord("!")] + [0] * 5))
    write("sdo_server", "block_upload", [4] + frame([0xA4, 0x01, 0x20, 0, 4, 0, 0, 0]) + frame([0xA3] + [0] * 7) + frame([0xA2, 4, 4, 0, 0, 0, 0, 0]))
    write("sdo_server", "block_download", [4] + frame([0xC6, 0x08, 0x10, 0, 3, 0, 0, 0]) + frame([0x81, 1, 2, 3, 0, 0, 0, 0]) + frame([0xD5, 0, 0, 0, 0, 0, 0, 0]))


def can_line_seeds():
    for i, line in enumerate([b"123#DEADBEEF", b"605#4000100000000000", b"123#", b"123#de.ad", b"123#R", b"123#R8",
                              b"(1700000000.123456) can0 585#4B00100092010000", b"(0.5) vcan0 080#", b"# comment"]):
        write("candump_line", f"line{i}", line)
    for i, line in enumerate([b"t1238DEADBEEF01020304", b"t60580123456789ABCDEF", b"t1230", b"r1238", b"t12321122ABCD", b"T123456781AA", b"z"]):
        write("slcan_line", f"line{i}", line)
    # async_can_streams: a chunk size byte, then a stream (SLCAN and candump lines, noise).
    write("async_can_streams", "slcan", b"\x03" + b"z\rt1238DEADBEEF01020304\r\x07F05\rt1230\r")
    write("async_can_streams", "candump", b"\x05" + b"# c\n(0.5) vcan0 585#4B00100092010000\n123#R\n605#40")


def rs232_seeds():
    fixture = ROOT / "tests/fixtures/kinco-rs232/manual-telegrams.txt"
    for row in fixture.read_text().splitlines():
        if row.startswith("#") or not row.strip():
            continue
        line, hexes = row.split(" ", 1)
        telegram = hexbytes(hexes)
        # Point-to-point: the drive's confirmation; multi-point: the echo first.
        answer = [telegram[0], 0x60] + telegram[2:5] + [0, 0, 0, 0]
        answer.append((-sum(answer)) & 0xFF)
        write("rs232_telegram", f"line{line}", [0, 3] + telegram + answer)
        write("rs232_telegram", f"line{line}_loop", [1, 10] + telegram + telegram + answer)


def srdo_seeds():
    normal = [0x01, 0x02]
    inverted = [b ^ 0xFF for b in normal]
    frame = lambda to_inverted, data: [0x01 if to_inverted else 0x00] + data + [0] * (8 - len(data))
    short = lambda to_inverted, data: [(len(data) << 3) | 0x04 | (0x01 if to_inverted else 0)] + data + [0] * (8 - len(data))
    pair = [10, 0] + short(False, normal) + [1, 0] + short(True, inverted)
    write("srdo_consumer", "pairs", [15, 100, 20] + pair * 3)
    write("srdo_consumer", "srvt_expired", [15, 100, 20] + [10, 0] + short(False, normal) + [30, 1] + short(True, inverted))
    write("srdo_consumer", "full_frames", [63, 50, 10] + [5, 0] + frame(False, [1] * 8) + [1, 0] + frame(True, [0xFE] * 8))


def description_seeds():
    copy_files("description_toml", [("codegen/tests/ui", "*.toml"), ("codegen/tests/fixtures", "*.toml")])
    for family in ["lafert-smartris", "kinco-fd", "lenze-smd", "ezwheel-swd"]:
        write("description_toml", family + ".toml", (ROOT / "descriptions" / family / "device.toml").read_bytes())
    copy_files("eds_reader", [("codegen/tests/eds", "*.eds"), ("codegen/tests/eds", "*.dcf")])
    overlay = (ROOT / "codegen/tests/ui/overlay_matches_eds.toml").read_bytes().replace(b"overlay_drive.eds", b"drive.eds")
    write("eds_overlay", "overlay_matches_eds", overlay + b"\0" + (ROOT / "codegen/tests/ui/overlay_drive.eds").read_bytes())
    fixture = ROOT / "codegen/tests/fixtures/overlay"
    toml = (fixture / "device.toml").read_bytes()
    write("eds_overlay", "fixture_overlay", toml + b"\0" + (fixture / "drive.eds").read_bytes())


# Seeds this script does not write: inputs fuzzing found (`finding_*`, kept beside their
# regression tests) and seeds written by hand (`hand_*`).
KEPT_PREFIXES = ("finding_", "hand_")


CONFIG_FILE = """# A drive's configuration, read by `drivegen config pull` (docs/config-file.md).
format = 1

[description]
name = "Lafert Smartris"
firmware = "2.4.2"
path = "/work/descriptions/lafert-smartris"

[drive]
target = "Modbus TCP 127.0.0.1:5020 unit 1"
pulled_at = "2026-11-27T21:40:00Z"

[identity]
fw_release = 242

[parameters]
speed_ramp_up = { value = "2000 ms", raw = 2000, unit = "ms" }
brake_mode = { value = "manual", raw = 1 }
"huge one" = { value = "18446744073709551615", raw = "18446744073709551615" }
label = { value = "ab", raw = [97, 98, 0] }
ratio = { value = "0.5", raw = 0.5 }

[unread]
dac_config = "not both readable and writable over Modbus"
"""


def config_file_seeds():
    """`drivegen config pull` files (docs/config-file.md): whole, cut short, another format."""
    text = CONFIG_FILE.encode()
    write("config_file", "pulled.toml", text)
    write("config_file", "truncated.toml", text[: text.index(b"brake_mode") + 20])
    write("config_file", "format2.toml", text.replace(b"format = 1", b"format = 2"))


def network_router_seeds():
    """The network core: a node subscribed and claimed, its SDO answer, PDO, EMCY, heartbeats and
    a silence long enough to lose it; and a neighbour's frames it must not get."""
    def frame(cob, data):
        return [0, cob & 0xFF, cob >> 8, len(data)] + data + [0] * (8 - len(data))
    node5 = [4, 4, 7, 2, 4, 5, 4, 100]
    answer = frame(0x585, [0x43, 0x00, 0x10, 0x00, 0x92, 0x01, 0x02, 0x00])
    traffic = frame(0x185, [1, 2]) + frame(0x085, [0x10, 0x23, 1, 0, 0, 0, 0, 0]) + frame(0x705, [0])
    silence = [1, 50, 1, 200, 1, 200] + frame(0x705, [0x05])
    write("network_router", "one_node", node5 + answer + traffic + silence + [3, 4])
    write("network_router", "neighbour", node5 + frame(0x586, [0x43] + [0] * 7) + frame(0x186, [9]) + [1, 10])


def network_file_seeds():
    """`drivegen network boot` files (docs/network.md): whole, cut short, a bad node id."""
    text = NETWORK_FILE.encode()
    write("network_file", "network.toml", text)
    write("network_file", "truncated.toml", text[: text.index(b"heartbeat_ms") + 5])
    write("network_file", "node_id_0.toml", text.replace(b"id = 5", b"id = 0"))
    write("network_file", "pdos.toml", (NETWORK_FILE + NETWORK_PDOS).encode())


NETWORK_PDOS = """
[[node.tpdo]]
number = 1
transmission_type = 254
event_timer = 50
inhibit_time = 10
mapping = ["statusword", "modes_of_operation_display"]

[[node.rpdo]]
number = 5
cob_id = 0x2A6
mapping = ["controlword"]
"""


NETWORK_FILE = """format = 1

[[node]]
id = 5
description = "../descriptions/lafert-smartris"
identity = { vendor_id = 0x0DD0, product_code = 7, revision = 1 }
heartbeat_ms = 100
start = true
parameters = { speed_ramp_up = "2000 ms", operation_mode = "velocity", limit = 12 }

[[node]]
id = 6
description = "../descriptions/kinco-fd"
start = false

[node.parameters]
target_speed = "100 rpm"
"""


def modbus_tcp_pipeline_seeds():
    """Answers to the pipeline's reads of one register (transaction ids from 1): in order, last
    first, behind a stale answer, split one byte a read, and an exception."""

    def answer(tid, value, unit=1):
        return struct.pack(">HHHBBBH", tid, 0, 5, unit, 0x03, 2, value)

    in_order = b"".join(answer(t, t * 10) for t in range(1, 9))
    write("modbus_tcp_pipeline", "in_order", bytes([63, 0]) + in_order)
    write("modbus_tcp_pipeline", "one_byte_a_read", bytes([0, 0]) + in_order)
    write("modbus_tcp_pipeline", "stale_first",
          bytes([63, 0]) + answer(0xFFFF, 1) + answer(1, 2, unit=2) + in_order)
    write("modbus_tcp_pipeline", "exception",
          bytes([7, 0]) + struct.pack(">HHHBBB", 1, 0, 3, 1, 0x83, 0x02) + in_order[11:])


def clear_generated_seeds():
    """Removes the seeds this script writes; the others (`KEPT_PREFIXES`) stay."""
    for target in SEEDS.iterdir():
        if target.is_dir():
            for seed in target.iterdir():
                if not seed.name.startswith(KEPT_PREFIXES):
                    seed.unlink()


def gateway_file_seeds():
    """`drivegen gateway` files (docs/gateway.md): whole, cut short, a drive name unfit for a topic."""
    text = GATEWAY_FILE.encode()
    write("gateway_file", "gateway.toml", text)
    write("gateway_file", "truncated.toml", text[: text.index(b"interval_ms") + 5])
    write("gateway_file", "topic_name.toml", text.replace(b'"left"', b'"left/#"'))
    write("gateway_file", "pdo_on_a_shared_bus.toml", GATEWAY_PDO_FILE.encode())


# Two CANopen drives by PDO on one bus: one at SYNC, one by its event timer.
def gateway_pdo_drive(name, description, node, interval, parameters, pdo):
    return (
        f'\n[[drive]]\nname = "{name}"\ndescription = "../descriptions/{description}"\n'
        f'bus = {{ can = "socketcan:can0", node_id = {node}, timeout_ms = 200 }}\n'
        f"interval_ms = {interval}\nparameters = {parameters}\npdo = {pdo}\n"
    )


GATEWAY_PDO_FILE = (
    "format = 1\n"
    + gateway_pdo_drive("sync", "ezwheel-swd", 16, 20, '["statusword", "position_actual_value"]', "true")
    + "pdo_start = true\n"
    + gateway_pdo_drive("event", "kinco-fd", 1, 50, '["statusword", "position_actual"]', '"event"')
)


GATEWAY_FILE = """format = 1
read_only = false

[mqtt]
host = "127.0.0.1"
port = 1883
username = "gateway"
password_env = "GATEWAY_PASSWORD"
ca_file = "ca.pem"
client_cert_file = "gw.pem"
client_key_file = "gw.key"

[[drive]]
name = "left"
description = "../descriptions/lafert-smartris"
bus = { modbus_tcp = "127.0.0.1:5020", unit = 3, timeout_ms = 200, rs232_loop = true }
interval_ms = 100
publish_every_poll = true
parameters = ["bus_dc_link", "speed_ramp_up"]
writable = ["speed_ramp_up"]
"""
def cyclic_feedback_seeds():
    """A CSP axis enabled through its RPDO, then following (statusword, position TPDOs)."""
    tpdos = [(0x0250, 0), (0x0237, 0), (0x1237, 10_000), (0x3237, 0)]
    data = bytearray([0x80])
    for status, actual in tpdos:
        data += bytes([6]) + struct.pack("<Hi", status, actual)
    write("cyclic_feedback", "enable_then_follow", data)


if __name__ == "__main__":
    clear_generated_seeds()
    modbus_seeds()
    sdo_client_seeds()
    sdo_server_seeds()
    can_line_seeds()
    rs232_seeds()
    srdo_seeds()
    description_seeds()
    config_file_seeds()
    network_router_seeds()
    network_file_seeds()
    gateway_file_seeds()
    modbus_tcp_pipeline_seeds()
    cyclic_feedback_seeds()
