"""python canopen 2.4.1's LSS master (`canopen.lss.LssMaster`) against the simulated SWD.

    lss_master.py DRIVEGEN_BINARY DESCRIPTION

Starts `drivegen sim DESCRIPTION --can candump:stdio` (the SWD at its default node id 16, serial
number 0x5A5A0001) as a child and relays frames between its stdio and python-can's virtual bus.
Then, as LssMaster: inquires the node id and the LSS address (vendor-ID, product code,
revision, serial number) in configuration state, switches back, selects the node by that
address (switch state selective), configures node id 5, stores, and resets the node over NMT.
The node must boot up as 5 (boot-up on 705h) and answer an SDO upload of its vendor-ID there.
Prints the values and "ok" last, exits 0 on success; prints the failed check and exits 1
otherwise. The simulator child is stopped by its PID on exit.
"""

import logging
import os
import sys
import threading

import canopen
from canopen import lss as cs

from canopen_relay import master_of_simulator

SERIAL = 0x5A5A0001


def boot_up_waiter(network, node_id):
    """An event set when node `node_id` sends its boot-up (heartbeat with state 0)."""
    booted = threading.Event()

    def on_heartbeat(can_id, data, timestamp):
        if data[:1] == b"\x00":
            booted.set()

    network.subscribe(0x700 + node_id, on_heartbeat)
    return booted


def scenario(network):
    lss = network.lss
    lss.RESPONSE_TIMEOUT = 2.0
    lss.send_switch_state_global(lss.CONFIGURATION_STATE)
    node_id = lss.inquire_node_id()
    assert node_id == 16, f"inquired node id {node_id}, the SWD's default is 16"
    address = [lss.inquire_lss_address(c) for c in (
        cs.CS_INQUIRE_VENDOR_ID, cs.CS_INQUIRE_PRODUCT_CODE, cs.CS_INQUIRE_REVISION_NUMBER,
        cs.CS_INQUIRE_SERIAL_NUMBER)]
    assert address[0] == 0x515, f"vendor-ID {address[0]:#x}, SWD manual line 1129 says 0x515"
    assert address[3] == SERIAL, f"serial number {address[3]:#x}, preset {SERIAL:#x}"
    print("inquired node id", node_id, "identity", [hex(w) for w in address], flush=True)
    lss.send_switch_state_global(lss.WAITING_STATE)

    assert lss.send_switch_state_selective(*address), "no answer to the selective switch"
    lss.configure_node_id(5)
    lss.store_configuration()
    lss.send_switch_state_global(lss.WAITING_STATE)

    booted = boot_up_waiter(network, 5)
    network.nmt.send_command(0x81)  # reset node, every node
    assert booted.wait(5.0), "no boot-up on 705h after the NMT reset"
    node = canopen.RemoteNode(5, canopen.ObjectDictionary())
    network.add_node(node)
    node.sdo.RESPONSE_TIMEOUT = 2.0
    vendor = int.from_bytes(node.sdo.upload(0x1018, 1), "little")
    assert vendor == 0x515, f"SDO upload of 1018h sub 1 at node 5: {vendor:#x}"
    print("booted as node 5, 1018h sub 1 =", hex(vendor), flush=True)


def main():
    logging.basicConfig(level=logging.ERROR)
    binary, description = sys.argv[1], sys.argv[2]
    booted = {}

    def prepare(network):
        booted["16"] = boot_up_waiter(network, 16)

    def run(network):
        assert booted["16"].wait(20.0), "the simulated SWD did not boot up on 710h"
        scenario(network)

    sim_args = [description, "--set", "vendor_id=0x515", "--set", f"serial_number={SERIAL:#x}"]
    errors = (canopen.lss.LssError, canopen.SdoCommunicationError, canopen.SdoAbortedError)
    master_of_simulator(binary, sim_args, f"drivegen-lss-{os.getpid()}", run, prepare, errors)
    print("ok", flush=True)


if __name__ == "__main__":
    main()
