"""python canopen 2.4.1 as the SDO master of the simulated Kinco FD, through the EDS drivegen
exports from the Kinco description.

    kinco_sdo_master.py EDS_PATH NODE_ID

The simulated node is on the other end of this process's stdio: frames arrive on stdin and leave
on stdout as candump compact lines (`601#2B40600006000000`), relayed to python-can's virtual
bus. Runs the manual's speed-mode objects by their EDS names (section 11.5: mode 3, target speed
150 rpm = 409600 DEC, controlword 0x0F), reads them back, checks the store command's allowed
values and an abort. Exits 0 on success; prints the failed check on stderr and exits 1.
"""

import logging
import sys


from canopen.sdo.exceptions import SdoAbortedError
from canopen_relay import master_on_stdio


def aborted(action):
    try:
        action()
    except SdoAbortedError as e:
        return e.code
    raise AssertionError("expected an SDO abort")


def scenario(node):
    node.sdo.RESPONSE_TIMEOUT = 1.0
    node.sdo["modes_of_operation"].raw = 3
    node.sdo["target_velocity"].raw = 409600
    node.sdo["controlword"].raw = 0x0F
    assert node.sdo["modes_of_operation"].raw == 3, "mode 3"
    assert node.sdo["target_velocity"].raw == 409600, "150 rpm = 409600 DEC (line 2364)"
    assert node.sdo["controlword"].raw == 0x0F, "controlword"
    # 2FF0h sub 1 takes 1 (store) and 10 (initialise) only (line 2117).
    node.sdo.download(0x2FF0, 1, bytes([1]))
    node.sdo.download(0x2FF0, 1, bytes([10]))
    assert aborted(lambda: node.sdo.download(0x2FF0, 1, bytes([2]))) != 0, "2 is no command"
    assert aborted(lambda: node.sdo.download(0x6041, 0, b"\x00\x00")) == 0x06010002, "read-only"
    assert node.object_dictionary[0x6510][0x0C].name == "rs485_protocol", "6510h sub 0x0C by name"


def main():
    logging.basicConfig(level=logging.ERROR)
    eds, node_id = sys.argv[1], int(sys.argv[2], 0)
    _, network, node = master_on_stdio("kinco-sdo-master", eds, node_id)
    try:
        scenario(node)
    except AssertionError as failed:
        print(f"FAILED: {failed}", file=sys.stderr)
        return 1
    finally:
        network.disconnect()
    return 0


if __name__ == "__main__":
    sys.exit(main())
