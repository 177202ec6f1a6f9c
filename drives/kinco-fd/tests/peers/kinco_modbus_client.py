"""pymodbus 3.16.1 as a Modbus client of the drivegen simulator serving the Kinco FD description.

    kinco_modbus_client.py tcp 127.0.0.1:PORT

Sends the register writes of the manual's speed-mode message table (section 10.5, lines
2518-2520: mode 3, target speed 0x00085555, controlword 0x0F), reads them back, and checks the
refusals: a read of an unknown register (answered with function code 0x81, line 2424) and a
write to the read-only statusword (0x86, line 2440). Prints "ok" and exits 0 on success, prints
the failed check and exits 1 otherwise.
"""

import sys

from pymodbus.client import ModbusTcpClient

UNIT = 1


def registers(result, what):
    assert not result.isError(), f"{what}: {result}"
    return result.registers


def refused(result, code, what):
    assert result.isError(), f"{what}: expected exception {code:#04x}, got {result}"
    assert result.exception_code == code, f"{what}: exception {result.exception_code:#04x}"


def main():
    host, port = sys.argv[2].rsplit(":", 1)
    client = ModbusTcpClient(host, port=int(port), timeout=2, retries=0)
    if not client.connect():
        raise SystemExit(f"cannot connect to {sys.argv[2]}")
    try:
        assert not client.write_register(0x3500, 3, device_id=UNIT).isError(), "mode 3"
        assert not client.write_registers(0x6F00, [0x5555, 0x0008], device_id=UNIT).isError(), "target speed"
        assert not client.write_register(0x3100, 0x000F, device_id=UNIT).isError(), "controlword 0x0F"
        mode = registers(client.read_holding_registers(0x3500, count=1, device_id=UNIT), "mode")
        assert mode == [3], f"mode 3, got {mode}"
        speed = registers(client.read_holding_registers(0x6F00, count=2, device_id=UNIT), "target speed")
        assert speed == [0x5555, 0x0008], f"target speed low word first, got {speed}"
        refused(client.read_holding_registers(0x0001, count=1, device_id=UNIT), 0x02, "unknown register")
        refused(client.write_register(0x3200, 1, device_id=UNIT), 0x02, "read-only statusword")
    except AssertionError as failed:
        print(f"FAILED: {failed}")
        return 1
    finally:
        client.close()
    print("ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
