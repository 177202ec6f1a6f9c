"""A python-canopen LocalNode reached through python-can's `slcan` interface over TCP.

    slcan_peer.py EDS NODE_ID PORT

python-can connects to 127.0.0.1:PORT (the Rust test listens there) and speaks SLCAN; the node
sends a boot-up once the channel is open. It exits when the connection closes.
"""
import sys
import time

import canopen


def main():
    eds, node_id, port = sys.argv[1], int(sys.argv[2], 0), int(sys.argv[3])
    network = canopen.Network()
    network.connect(interface="slcan", channel=f"socket://127.0.0.1:{port}",
                    sleep_after_open=0, bitrate=500000)
    node = canopen.LocalNode(node_id, eds)
    network.add_node(node)
    node.nmt.send_command(0x81)
    node.nmt.send_command(0x80)
    try:
        while network.notifier is not None and network.bus is not None:
            time.sleep(0.1)
            if network.notifier.exception is not None:
                break
    finally:
        network.disconnect()


if __name__ == "__main__":
    main()
