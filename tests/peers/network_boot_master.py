"""python canopen 2.4.1 boots one node the way `drivebus::canopen::network::boot` does, for the
frame count of issue 31's benchmark (drivesim/tests/network_boot_frames.rs).

    network_boot_master.py EDS_PATH NODE_ID VENDOR_ID

The node is on the other end of this process's stdio (candump compact lines, relayed to
python-can's virtual bus). The steps: read 1000h; read 1018h sub 1 and compare; write
1017h = 100 ms; TPDO1 = statusword (6041h) and mode display (6061h), transmission type 254,
event timer 20 ms, through PdoMap.save() (disable, type, timer, count 0, entries, count,
enable); write 6081h = 1234; NMT start. Exits 0 on success, prints the failed check on stderr
and exits 1 (stdout carries the frames).
"""

import logging
import sys
import time

import canopen

from canopen_relay import master_on_stdio


def boot(node, vendor):
    node.sdo.RESPONSE_TIMEOUT = 1.0
    node.sdo.upload(0x1000, 0)
    found = int.from_bytes(node.sdo.upload(0x1018, 1), "little")
    assert found == vendor, f"vendor-ID {found:#x}"
    node.sdo.download(0x1017, 0, (100).to_bytes(2, "little"))
    tpdo = node.tpdo[1]
    tpdo.clear()
    tpdo.add_variable(0x6041)
    tpdo.add_variable(0x6061)
    tpdo.cob_id = 0x180 + node.id
    tpdo.trans_type = 254
    tpdo.event_timer = 20
    tpdo.enabled = True
    tpdo.save()
    node.sdo.download(0x6081, 0, (1234).to_bytes(4, "little"))
    node.nmt.state = "OPERATIONAL"


def main():
    logging.basicConfig(level=logging.ERROR)
    eds, node_id = sys.argv[1], int(sys.argv[2], 0)
    vendor = int(sys.argv[3], 0)
    bus, network, node = master_on_stdio("network-boot-master", eds, node_id)
    try:
        boot(node, vendor)
        # The relay thread copies the NMT start to stdout: give it the time before exiting.
        time.sleep(0.3)
    except (AssertionError, canopen.SdoAbortedError, canopen.SdoCommunicationError) as failed:
        print(f"FAILED: {failed}", file=sys.stderr)
        sys.exit(1)
    finally:
        network.disconnect()
        bus.shutdown()


if __name__ == "__main__":
    main()
