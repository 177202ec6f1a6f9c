"""A pymodbus 3.16.1 server the Rust peer tests talk to.

    modbus_server.py tcp             -> serves Modbus TCP on 127.0.0.1, port chosen by the OS;
                                        prints "PORT <n>" on stdout once listening
    modbus_server.py rtu-over-tcp    -> like tcp, with RTU frames (a serial gateway)
    modbus_server.py rtu <pty path>  -> serves Modbus RTU on the pty; prints "READY" once open
    ... --firmware N                 -> FW RELEASE CUSTOMER (holding 0x01FF) holds N (default 242,
                                        the release the Lafert description covers)
    ... --units 1,2,3,4              -> several units on the one line or connection, each with the
                                        map below and its own id in 0x0028; a request to another
                                        id gets no answer, as on an RS-485 line (default: unit 1)

Unit 1 holds a Lafert-like register map (non-shared tables, wire address 0 = first value):
  holding 0x0000..=0x00FF  value = address, except 0x0003 (full-scale velocity) = 3000 and
                           0x0028 (drive address) = 1
  holding 0x01FF           the firmware release (--firmware)
  input   0x0060..=0x0070  value = 0x1000 + address, except 0x006B/0x006C = 0x5678/0x1234
                           (AXIS POSITION LOW/HIGH = 0x12345678)
  coils   0..=31           True at even addresses
  discrete inputs 0..=15   True at addresses divisible by 3
Anything else answers exception 0x02. Writing 0x0028 with a value outside 1..=247 answers
exception 0x03 (illegal data value), as the drive documents; so does writing the speed setpoint
0x0042 beyond +-3000 rpm (the full-scale velocity of an L motor, holding 0x0003, which a client
cannot know from the register's type: it reads 0x0003 first).
The process exits when stdin closes, so a test that dies cannot leave it behind.
"""

import asyncio
import sys

from pymodbus import FramerType
from pymodbus.constants import ExcCodes
from pymodbus.server import ModbusSerialServer, ModbusTcpServer
from pymodbus.simulator import DataType, SimData, SimDevice

FULL_SCALE_REGISTER = 0x0003
ADDRESS_REGISTER = 0x0028
SPEED_SETPOINT = 0x0042
FULL_SCALE_VELOCITY = 3000
FIRMWARE_RELEASE = 0x01FF


def option(name, default):
    """The integer after `name` on the command line, else `default`."""
    if name in sys.argv:
        return int(sys.argv[sys.argv.index(name) + 1], 0)
    return default


def units():
    """The unit ids --units names (default: unit 1 alone)."""
    if "--units" in sys.argv:
        return [int(u, 0) for u in sys.argv[sys.argv.index("--units") + 1].split(",")]
    return [1]


def holding(unit):
    values = list(range(0x100))
    values[FULL_SCALE_REGISTER] = FULL_SCALE_VELOCITY
    values[ADDRESS_REGISTER] = unit
    firmware = option("--firmware", 242)
    return [SimData(address=0, values=values, datatype=DataType.REGISTERS),
            SimData(address=FIRMWARE_RELEASE, values=[firmware], datatype=DataType.REGISTERS)]


def inputs():
    values = [0x1000 + a for a in range(0x60, 0x71)]
    values[0x6B - 0x60] = 0x5678
    values[0x6C - 0x60] = 0x1234
    return [SimData(address=0x60, values=values, datatype=DataType.REGISTERS)]


def signed(register):
    """A register value as i16."""
    return register - 0x10000 if register >= 0x8000 else register


async def action(function_code, start_address, address, count, current_registers, set_values):
    """Enforces the drive address range on writes."""
    if function_code in (0x06, 0x10) and set_values is not None:
        for offset, value in enumerate(set_values):
            if address + offset == ADDRESS_REGISTER and not 1 <= int(value) <= 247:
                return ExcCodes.ILLEGAL_VALUE
            if address + offset == SPEED_SETPOINT and abs(signed(int(value))) > FULL_SCALE_VELOCITY:
                return ExcCodes.ILLEGAL_VALUE
    return None


def device(unit):
    coils = [SimData(address=0, values=[a % 2 == 0 for a in range(32)], datatype=DataType.BITS)]
    discrete = [SimData(address=0, values=[a % 3 == 0 for a in range(16)], datatype=DataType.BITS)]
    return SimDevice(id=unit, simdata=(coils, discrete, holding(unit), inputs()), action=action)


def devices():
    """One device per unit."""
    return [device(unit) for unit in units()]


def silence_others():
    """With --units, a request to an id nobody holds is dropped on arrival and gets no answer,
    as on an RS-485 line (pymodbus would answer exception 0x04 from its simulator)."""
    if "--units" not in sys.argv:
        return None
    ids = set(units())
    return lambda sending, pdu: pdu if sending or pdu.dev_id in ids else None


async def wait_for_stdin_eof():
    loop = asyncio.get_running_loop()
    await loop.run_in_executor(None, sys.stdin.read)


async def main():
    mode = sys.argv[1]
    served, trace = devices(), silence_others()
    if mode == "tcp":
        server = ModbusTcpServer(served, address=("127.0.0.1", 0), trace_pdu=trace)
    elif mode == "rtu-over-tcp":
        server = ModbusTcpServer(served, address=("127.0.0.1", 0), framer=FramerType.RTU,
                                 trace_pdu=trace)
    elif mode == "rtu":
        server = ModbusSerialServer(served, port=sys.argv[2], baudrate=19200, trace_pdu=trace)
    else:
        raise SystemExit(f"unknown mode {mode!r}")
    await server.serve_forever(background=True)
    if mode != "rtu":
        port = server.transport.sockets[0].getsockname()[1]
        print(f"PORT {port}", flush=True)
    else:
        print("READY", flush=True)
    await wait_for_stdin_eof()
    await server.shutdown()


if __name__ == "__main__":
    asyncio.run(main())
