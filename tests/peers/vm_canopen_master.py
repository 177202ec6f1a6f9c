"""python canopen 2.4.1 over python-can's `socketcan` interface: an independent CANopen master
reading the simulated drive through the EDS drivegen exported, inside the VM of
scripts/vm-can-test.

    vm_canopen_master.py EDS NODE_ID ROUND_TRIPS

Reads 1000h, 1018h sub 1 and the node id object 2101h, writes 2102h (termination resistor) and
reads it back, checks an abort for a missing object, then times ROUND_TRIPS expedited uploads of
1000h. Prints `VMBENCH python_sdo_per_s N` and `ok`; exits 1 with the failed check otherwise.
"""

import sys
import time

import canopen
from canopen.sdo.exceptions import SdoAbortedError


def main():
    eds, node_id, trips = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    network = canopen.Network()
    network.connect(interface="socketcan", channel="vcan0")
    try:
        node = network.add_node(node_id, eds)
        node.sdo.RESPONSE_TIMEOUT = 2.0
        # Through the EDS's object dictionary: its types decode the values.
        device_type = node.sdo[0x1000].raw
        vendor = node.sdo[0x1018][1].raw
        read_id = node.sdo[0x2101].raw
        print(f"device type {device_type:#010x}, vendor-ID {vendor:#010x}, node id {read_id}")
        if read_id != node_id:
            print(f"FAIL: 2101h reads {read_id}, expected {node_id}")
            return 1
        node.sdo[0x2102].raw = 0
        if node.sdo[0x2102].raw not in (0, False):
            print("FAIL: 2102h did not read back 0")
            return 1
        try:
            node.sdo.upload(0x5FFF, 0)
            print("FAIL: 5FFFh was answered")
            return 1
        except SdoAbortedError as e:
            if e.code != 0x06020000:
                print(f"FAIL: abort {e.code:#010x} for a missing object")
                return 1
        start = time.perf_counter()
        for _ in range(trips):
            node.sdo.upload(0x1000, 0)
        elapsed = time.perf_counter() - start
        print(f"VMBENCH python_sdo_per_s {trips / elapsed:.0f}")
        print("ok")
        return 0
    finally:
        network.disconnect()


if __name__ == "__main__":
    sys.exit(main())
