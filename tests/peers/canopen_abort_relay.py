"""The canopen relay (canopen_relay.py), reporting each SDO abort its LocalNode receives: the
abort's 8 bytes are sent back on COB-ID 0x7E0 (unused by the predefined connection set and
LSS), so a test sees that the abort reached the peer.

    canopen_abort_relay.py EDS NODE_ID
"""
import canopen_relay

ABORT_SEEN_COB_ID = 0x7E0


def install(node):
    def on_request(can_id, data, timestamp):
        if len(data) == 8 and data[0] == 0x80:
            node.network.send_message(ABORT_SEEN_COB_ID, bytes(data))

    node.network.subscribe(0x600 + node.id, on_request)


if __name__ == "__main__":
    canopen_relay.main(install)
