"""python canopen 2.4.1's BaseNode402 as an independent CiA 402 master of the simulated Kinco FD
(issue 32 item 5), through the EDS drivegen exports from the Kinco description.

    kinco_motion_master.py EDS_PATH NODE_ID

The simulated node is on the other end of this process's stdio (candump compact lines, as in
canopen_relay.py). Without PDOs BaseNode402 reads the statusword and writes the controlword by
SDO. The master brings the drive to OPERATION ENABLED, runs `homing()` (method 17, the switch
the simulator places), switches to PROFILED POSITION and moves by SDO to 50,000 increments with
the set-point handshake (controlword bit 4, statusword bit 12), waits for target reached (bit
10) and reads the actual position within the position window 6067h.

The Kinco manual documents neither 6502h (supported drive modes) nor 6064h: BaseNode402's mode
check is given the modes the manual lists (1, 3, 4, 6, 7: the bits of 6502h), and the position is
read from Kinco's Pos_Actual 6063h (manual line 1945). Exits 0 on success; prints the failed
check on stderr and exits 1.
"""

import logging
import os
import sys
import time

import can
import canopen

from canopen_relay import relay_stdio

# 6502h bits of the modes the Kinco manual lists (line 1937): pp 0, pv 2, tq 3, hm 5, ip 6.
KINCO_MODES = 0x01 | 0x04 | 0x08 | 0x20 | 0x40
POSITION = 50_000


def wait_for(node, mask, value, what, seconds=10.0):
    end = time.monotonic() + seconds
    while node.sdo[0x6041].raw & mask != value:
        if time.monotonic() > end:
            raise AssertionError(f"{what}: statusword {node.sdo[0x6041].raw:#06x}")
        time.sleep(0.005)


def scenario(node):
    node.sdo.RESPONSE_TIMEOUT = 1.0
    node._op_mode_support = KINCO_MODES
    node.state = "OPERATION ENABLED"
    assert node.state == "OPERATION ENABLED", f"state {node.state}"

    node.sdo[0x6098].raw = 17
    node.sdo[0x6099][1].raw = 100_000
    node.sdo[0x609A].raw = 1_000_000
    assert node.homing(timeout=10), "homing() reported failure"
    assert node.op_mode == "HOMING", f"mode {node.op_mode}"

    node.op_mode = "PROFILED POSITION"
    assert node.op_mode == "PROFILED POSITION", f"mode {node.op_mode}"
    node.sdo[0x6081].raw = 200_000
    node.sdo[0x6083].raw = 1_000_000
    node.sdo[0x6084].raw = 1_000_000
    node.sdo[0x607A].raw = POSITION
    node.controlword = 0x2F  # bit 4 low: the next write is the edge
    node.controlword = 0x3F  # new set-point, change immediately, absolute
    wait_for(node, 0x1000, 0x1000, "set-point acknowledge")
    node.controlword = 0x2F
    wait_for(node, 0x1400, 0x0400, "target reached")
    window = node.sdo[0x6067].raw
    position = node.sdo[0x6063].raw
    assert abs(position - POSITION) <= window, f"position {position}, window {window}"
    print(f"homed, moved to {position} (window {window})", file=sys.stderr, flush=True)


def main():
    logging.basicConfig(level=logging.ERROR)
    eds, node_id = sys.argv[1], int(sys.argv[2], 0)
    channel = f"kinco-motion-master-{os.getpid()}"
    relay = can.Bus(interface="virtual", channel=channel)
    network = canopen.Network()
    network.connect(interface="virtual", channel=channel)
    node = canopen.BaseNode402(node_id, eds)
    network.add_node(node)
    relay_stdio(relay)
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
