"""python-canopen's BaseNode402 as an independent CiA 402 master of a node served by the Rust
test on the other end of stdin/stdout (candump compact lines, as in canopen_relay.py).

    cia402_master.py EDS NODE_ID

Without PDOs BaseNode402 reads the statusword and writes the controlword by SDO. It walks the node
to operation enabled, back to switch on disabled, and sets profile velocity mode; each reached
state goes to stderr as `reached <STATE>`. Exit status 0 when every step was confirmed.
"""
import logging
import sys

import can
import canopen

from canopen_relay import relay_stdio


def scenario(node):
    for target in ("OPERATION ENABLED", "SWITCHED ON", "SWITCH ON DISABLED"):
        node.state = target
        print(f"reached {node.state}", file=sys.stderr, flush=True)
        if node.state != target:
            return False
    node.op_mode = "PROFILED VELOCITY"
    print(f"mode {node.op_mode}", file=sys.stderr, flush=True)
    return node.op_mode == "PROFILED VELOCITY"


def main():
    logging.basicConfig(level=logging.ERROR)
    eds, node_id = sys.argv[1], int(sys.argv[2], 0)
    channel = f"drivegen-master-{id(sys)}"
    relay = can.Bus(interface="virtual", channel=channel)
    network = canopen.Network()
    network.connect(interface="virtual", channel=channel)
    node = canopen.BaseNode402(node_id, eds)
    network.add_node(node)

    relay_stdio(relay)
    ok = scenario(node)
    network.disconnect()
    relay.shutdown()
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
