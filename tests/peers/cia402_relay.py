"""A CiA 402 device double: canopen_relay.py's LocalNode plus a write callback on the controlword
(0x6040) that runs the CiA 402 power drive system state machine and publishes the statusword
(0x6041); the mode display (0x6061) follows the requested mode (0x6060).

    cia402_relay.py EDS NODE_ID [FAULT_RESET_HOLD_MS]

Test hooks: writing 1 to 0x2001 raises a fault (fault reaction active, then fault); writing 1 to
0x2002 activates safe torque off (switch on disabled; 0x2003 bit 0 mirrors it). Fault reset acts on
a rising edge of controlword bit 7 and, with FAULT_RESET_HOLD_MS > 0, only once the bit has stayed
high that long.
"""
import sys
import threading
import time

import canopen_relay

# Statusword of each state: bit 9 (remote) and, with the power stage on, bit 4 (voltage enabled).
STATUSWORD = {
    "not ready to switch on": 0x0200,
    "switch on disabled": 0x0240,
    "ready to switch on": 0x0231,
    "switched on": 0x0233,
    "operation enabled": 0x0237,
    "quick stop active": 0x0217,
    "fault reaction active": 0x021F,
    "fault": 0x0218,
}


def command(controlword):
    """The CiA 402 device control command a controlword encodes (bits 0-3 and 7)."""
    if controlword & 0x82 == 0x00:
        return "disable voltage"
    if controlword & 0x86 == 0x02:
        return "quick stop"
    if controlword & 0x87 == 0x06:
        return "shutdown"
    if controlword & 0x8F == 0x07:
        return "switch on"  # also disable operation
    if controlword & 0x8F == 0x0F:
        return "enable operation"
    return None


TRANSITIONS = {
    ("switch on disabled", "shutdown"): "ready to switch on",  # 2
    ("ready to switch on", "switch on"): "switched on",  # 3
    ("ready to switch on", "enable operation"): "switched on",  # 3 (then 4 on the next write)
    ("switched on", "enable operation"): "operation enabled",  # 4
    ("operation enabled", "switch on"): "switched on",  # 5
    ("switched on", "shutdown"): "ready to switch on",  # 6
    ("ready to switch on", "disable voltage"): "switch on disabled",  # 7
    ("ready to switch on", "quick stop"): "switch on disabled",  # 7
    ("operation enabled", "shutdown"): "ready to switch on",  # 8
    ("operation enabled", "disable voltage"): "switch on disabled",  # 9
    ("switched on", "disable voltage"): "switch on disabled",  # 10
    ("switched on", "quick stop"): "switch on disabled",  # 10
    ("operation enabled", "quick stop"): "quick stop active",  # 11
    ("quick stop active", "disable voltage"): "switch on disabled",  # 12
}


def install(node, hold_ms):
    lock = threading.Lock()
    drive = {"state": "switch on disabled", "controlword": 0, "sto": False, "raised": None}

    def publish():
        node.set_data(0x6041, 0, STATUSWORD[drive["state"]].to_bytes(2, "little"), check_writable=False)
        node.set_data(0x2003, 0, bytes([1 if drive["sto"] else 0, 0]), check_writable=False)

    def reset_if_still_high(raised):
        with lock:
            if drive["state"] == "fault" and drive["raised"] == raised:
                drive["state"] = "switch on disabled"
                publish()

    def on_controlword(controlword):
        previous = drive["controlword"]
        drive["controlword"] = controlword
        rising = controlword & 0x80 and not previous & 0x80
        if not controlword & 0x80:
            drive["raised"] = None
        if drive["state"] == "fault":
            if rising:
                drive["raised"] = time.monotonic()
                if hold_ms == 0:
                    drive["state"] = "switch on disabled"
                else:
                    timer = threading.Timer(hold_ms / 1000, reset_if_still_high, (drive["raised"],))
                    timer.daemon = True
                    timer.start()
            return
        if drive["sto"] and drive["state"] == "switch on disabled":
            return
        drive["state"] = TRANSITIONS.get((drive["state"], command(controlword)), drive["state"])

    def on_write(index, subindex, od, data, **kwargs):
        if index not in (0x6040, 0x6060, 0x2001, 0x2002):
            return  # includes the device's own updates of 0x6041, 0x6061 and 0x2003
        value = int.from_bytes(data, "little", signed=index in (0x6060,))
        with lock:
            if index == 0x6040:
                on_controlword(value)
            elif index == 0x6060:
                node.set_data(0x6061, 0, data, check_writable=False)
                return
            elif index == 0x2001 and value:
                drive["state"] = "fault"
            elif index == 0x2002:
                drive["sto"] = bool(value)
                if drive["sto"]:
                    drive["state"] = "switch on disabled"
            else:
                return
            publish()

    node.add_write_callback(on_write)
    publish()


if __name__ == "__main__":
    hold = int(sys.argv[3]) if len(sys.argv) > 3 else 0
    canopen_relay.main(lambda node: install(node, hold))
