"""A pymodbus 3.16.1 Modbus RTU server playing a Lenze smd drive, for tests/peer_pymodbus.rs.

    smd_server.py <pty path> <configuration>   -> serves unit 10 on the pty; prints "READY"

<configuration> is the value of register #50: 400 and 507 lay the map out as PC400 / PC507
(manual 004_e90b7fce7c8d5710.txt, section 6.2); any other number serves the PC400 layout under
that number. The drive's rules the test relies on, from the manual:
  * one register per read, except 6 words at #24 (line 617) and 4 words at C99 (line 229);
    any other count answers exception 03;
  * #1, #48, #49 are write-only (Table 6): reading them answers exception 02, as does writing a
    read-only register;
  * writes need an unlock: #48 = 0 unlocks controls (#1, #40), #48 or #49 = C94 (0 here)
    unlocks parameters too; #1 bit 1 locks; a write while locked answers exception 01
    (section 4.5, line 416); #1 with several bits and no STOP answers exception 04 (line 571).
Instrumentation (not a drive register): holding #200 counts the writes the drive accepted.
C99 ("SMD 1.51" / "SMD 2.01", 4 words) is served from its register on, so the three registers
after it read as text here, unlike a real drive. The process exits when stdin closes.
"""

import asyncio
import sys

from pymodbus.constants import ExcCodes
from pymodbus.server import ModbusSerialServer
from pymodbus.simulator import DataType, SimData, SimDevice

UNIT = 10
DRIVE_CONTROL, SERIAL_SPEED, UNLOCK_CONTROLS, UNLOCK_PARAMETERS = 1, 40, 48, 49
WRITE_ONLY = {DRIVE_CONTROL, UNLOCK_CONTROLS, UNLOCK_PARAMETERS}
READ_ONLY = {19, 21, 22, 24, 25, 26, 27, 28, 29, 30, 50}
STATUS_BLOCK = 24
ACCEPTED_WRITES = 200
PASSWORD = 0
LOCK_BIT, STOP_BIT = 0x0002, 0x0004


def text_words(text):
    data = text.encode("ascii")
    return [data[i] << 8 | data[i + 1] for i in range(0, len(data), 2)]


class Smd:
    def __init__(self, configuration):
        self.configuration = configuration
        pc507 = configuration == 507
        self.c99 = 95 if pc507 else 89
        self.controls = False
        self.parameters = False
        values = [0] * 256
        values[19] = 69                     # drive family: smd (Note 2, line 581)
        values[22] = 0x0004                 # OEM defaults present (Table 9)
        values[24:30] = [513, 500, 0x6406, 0x010B, 0x0600, 0x0001]  # Table 10 example words
        values[30] = 100                    # motor voltage 100 %
        values[50] = configuration
        values[51] = 11                     # C01: Modbus control, speed from c40
        values[59], values[60] = 0, 500     # C10 0.0 Hz, C11 50.0 Hz
        values[61] = 50                     # C12 5.0 s
        values[88 if not pc507 else 94] = PASSWORD  # C94
        values[self.c99:self.c99 + 4] = text_words("SMD 2.01" if pc507 else "SMD 1.51")
        values[95 if not pc507 else 103] = 0        # c25 (PC400 #95 is c25; PC507 #95 is C99)
        self.values = values

    def read_allowed(self, address, count):
        if address in WRITE_ONLY or address == ACCEPTED_WRITES and count != 1:
            return ExcCodes.ILLEGAL_ADDRESS
        if count == 1 or (address, count) in ((STATUS_BLOCK, 6), (self.c99, 4)):
            return None
        return ExcCodes.ILLEGAL_VALUE

    def write(self, address, value):
        if address in READ_ONLY or address == ACCEPTED_WRITES:
            return ExcCodes.ILLEGAL_ADDRESS
        if address == UNLOCK_CONTROLS:
            self.controls |= value in (0, PASSWORD)
            self.parameters |= value == PASSWORD
        elif address == UNLOCK_PARAMETERS:
            self.parameters |= value == PASSWORD
        elif address == DRIVE_CONTROL:
            if not (self.controls or (value == LOCK_BIT and self.parameters)):
                return ExcCodes.ILLEGAL_FUNCTION
            if bin(value).count("1") > 1 and not value & STOP_BIT:
                return ExcCodes.DEVICE_FAILURE
            if value & LOCK_BIT:
                self.controls = self.parameters = False
        elif address == SERIAL_SPEED:
            if not self.controls:
                return ExcCodes.ILLEGAL_FUNCTION
        elif not self.parameters:
            return ExcCodes.ILLEGAL_FUNCTION
        return None


def device(smd):
    async def action(function_code, start_address, address, count, current_registers, set_values):
        if function_code in (0x03, 0x04):
            return smd.read_allowed(address, count)
        if function_code in (0x06, 0x10):
            if set_values is None:
                return None  # pymodbus asks again after the write, without values
            if len(set_values) != 1:
                return ExcCodes.ILLEGAL_VALUE   # FC 16 only for a single register (line 235)
            refused = smd.write(address, int(set_values[0]))
            if refused is None:
                current_registers[ACCEPTED_WRITES - start_address] += 1
            return refused
        return ExcCodes.ILLEGAL_FUNCTION

    registers = [SimData(address=0, values=smd.values, datatype=DataType.REGISTERS)]
    # pymodbus needs bit tables; the smd has none, and `action` refuses their function codes.
    bits = [SimData(address=0, values=[False], datatype=DataType.BITS)]
    # The smd treats FC 03 and FC 04 alike (line 237): both tables are the same map.
    return SimDevice(id=UNIT, simdata=(bits, bits, registers, registers), action=action)


async def wait_for_stdin_eof():
    loop = asyncio.get_running_loop()
    await loop.run_in_executor(None, sys.stdin.read)


async def main():
    port, configuration = sys.argv[1], int(sys.argv[2])
    server = ModbusSerialServer(device(Smd(configuration)), port=port, baudrate=9600)
    await server.serve_forever(background=True)
    print("READY", flush=True)
    await wait_for_stdin_eof()
    await server.shutdown()


if __name__ == "__main__":
    asyncio.run(main())
