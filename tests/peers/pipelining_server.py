"""Modbus TCP server for the pipelining peer test: pyModbusTCP 0.3.1, which reads each request
frame by frame from its connection and so answers requests sent back to back in one write
(pymodbus 3.16.1 answers only the first frame of a segment and drops the rest).

Registers (wire addresses), as in modbus_server.py:
  holding 0x0000..=0x00FF  value = address, except 0x0028 (drive address) = 1; a read past
                           0x00FF is exception 0x02
  input   0x0060..=0x0070  value = 0x1000 + address, except 0x006B/0x006C = 0x5678/0x1234

Listens on 127.0.0.1, port 0; prints "PORT <n>" once ready and serves until stdin closes.
"""

import sys

from pyModbusTCP.server import DataBank, ModbusServer


def main():
    bank = DataBank(h_regs_size=0x100, i_regs_size=0x71)
    holding = list(range(0x100))
    holding[0x28] = 1
    inputs = [0x1000 + a for a in range(0x60, 0x71)]
    inputs[0x6B - 0x60 : 0x6D - 0x60] = [0x5678, 0x1234]
    bank.set_holding_registers(0, holding)
    bank.set_input_registers(0x60, inputs)
    server = ModbusServer(host="127.0.0.1", port=0, no_block=True, data_bank=bank)
    server.start()
    # pyModbusTCP 0.3.1 has no public accessor for the port it bound (port 0 picks one).
    print(f"PORT {server._service.server_address[1]}", flush=True)
    sys.stdin.read()
    server.stop()


if __name__ == "__main__":
    main()
