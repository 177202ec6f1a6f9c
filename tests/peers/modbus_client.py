"""pymodbus 3.16.1 as a Modbus client of the drivegen simulator serving the Lafert Smartris
description (started with operation_mode preset to 2, velocity).

    modbus_client.py tcp 127.0.0.1:PORT
    modbus_client.py rtu /path/to/pty

Runs the manual's run sequence and the refusals the manual documents, asserting every answer;
prints "ok" and exits 0 on success, prints the failed check and exits 1 otherwise.
"""

import sys

from pymodbus.client import ModbusSerialClient, ModbusTcpClient

UNIT = 1


def connect(mode, target):
    if mode == "tcp":
        host, port = target.rsplit(":", 1)
        client = ModbusTcpClient(host, port=int(port), timeout=2, retries=0)
    else:
        client = ModbusSerialClient(port=target, baudrate=19200, timeout=2, retries=0)
    if not client.connect():
        raise SystemExit(f"cannot connect to {target}")
    return client


def registers(result, what):
    assert not result.isError(), f"{what}: {result}"
    return result.registers


def exception(result, code, what):
    assert result.isError(), f"{what}: expected exception {code:#04x}, got {result}"
    assert result.exception_code == code, f"{what}: exception {result.exception_code:#04x}, expected {code:#04x}"


def main():
    client = connect(sys.argv[1], sys.argv[2])
    try:
        status = registers(client.read_input_registers(0x0060, count=1, device_id=UNIT), "drive status")
        assert status == [0x0002], f"standby after power-on, got {status}"
        mode = registers(client.read_holding_registers(0x0207, count=1, device_id=UNIT), "operation mode")
        assert mode == [2], f"velocity mode, got {mode}"

        assert not client.write_register(0x0001, 0x0003, device_id=UNIT).isError(), "run (T2)"
        status = registers(client.read_input_registers(0x0060, count=1, device_id=UNIT), "drive status")
        assert status == [0x0001], f"run velocity, got {status}"
        assert not client.write_register(0x0042, 0xFC18, device_id=UNIT).isError(), "-1000 rpm"
        setpoint = registers(client.read_input_registers(0x0042, count=1, device_id=UNIT), "setpoint")
        assert setpoint == [0xFC18], f"setpoint read back from input 0x0042, got {setpoint}"
        block = registers(client.read_input_registers(0x0060, count=9, device_id=UNIT), "status block")
        assert len(block) == 9 and block[0] == 0x0001, f"status block {block}"

        exception(client.write_register(0x0001, 8, device_id=UNIT), 0x03, "control word 8")
        exception(client.write_register(0x0040, 0x8000, device_id=UNIT), 0x03, "negative ramp")
        exception(client.write_register(0x0003, 1, device_id=UNIT), 0x02, "read-only full scale")
        exception(client.read_holding_registers(0x0000, count=1, device_id=UNIT), 0x02, "write-only store")
        exception(client.read_holding_registers(0x7777, count=1, device_id=UNIT), 0x02, "unknown address")
        exception(client.write_registers(0x0042, [1, 2], device_id=UNIT), 0x01, "FC 0x10 not implemented")

        assert not client.write_register(0x0001, 0x0001, device_id=UNIT).isError(), "stop (T4)"
        status = registers(client.read_input_registers(0x0060, count=1, device_id=UNIT), "drive status")
        assert status == [0x0004], f"stop, got {status}"
        assert not client.write_register(0x0001, 0x0002, device_id=UNIT).isError(), "standby (T6)"
        status = registers(client.read_input_registers(0x0060, count=1, device_id=UNIT), "drive status")
        assert status == [0x0002], f"standby, got {status}"
    except AssertionError as failed:
        print(f"FAILED: {failed}")
        sys.exit(1)
    finally:
        client.close()
    print("ok")


if __name__ == "__main__":
    main()
