#!/usr/bin/env python3
"""A Festo FHPP direct-mode drive served by pymodbus (Debian 12: python3-pymodbus 3.0).

An independent Modbus peer for the rangefit linear-axis driver tests: the Modbus framing, the
function codes (0x17, 0x03, 0x10) and the register store are pymodbus's, not ours. The FHPP
telegram layout follows docs/protocols/fhpp_modbus.md: register k = byte 2k | byte 2k+1 << 8,
positions as little-endian int32 increments.

Usage: fhpp_pymodbus_server.py [increments_per_mm] [max_speed_mm_s]
Prints "PORT <n>" once listening on 127.0.0.1 (a free port); exits when stdin closes.
"""
import asyncio
import logging
import struct
import sys
import time

try:
    from pymodbus.datastore import (ModbusSequentialDataBlock, ModbusServerContext,
                                    ModbusSlaveContext)
    from pymodbus.server.async_io import ModbusTcpServer
except ImportError as err:  # the C++ test turns this into a clear failure
    print(f"MISSING python3-pymodbus (install it with scripts/deps.sh): {err}", flush=True)
    sys.exit(3)

CCON_ENABLE, CCON_STOP, CCON_RESET = 0x01, 0x02, 0x08
CPOS_HALT, CPOS_START, CPOS_HOME = 0x01, 0x02, 0x04
SCON_ENABLED, SCON_OPEN, SCON_FAULT, SCON_VLOAD, SCON_DIRECT = 0x01, 0x02, 0x08, 0x10, 0x40
SPOS_HALT, SPOS_ACK, SPOS_MC, SPOS_MOV, SPOS_REF = 0x01, 0x02, 0x04, 0x10, 0x80


class FhppDrive:
    """Enable/stop, halt, START and HOME handshakes with ACK, constant-speed motion."""

    def __init__(self, inc_per_mm, max_speed_mm_s):
        self.inc_per_mm = inc_per_mm
        self.max_speed = max_speed_mm_s
        self.prev_ccon = self.prev_cpos = 0
        self.enabled = self.open = self.halt = self.ack = self.referenced = False
        self.pct = 0
        self.p0 = self.target = int(100 * inc_per_mm)  # power-up at 100 mm
        self.t0 = time.monotonic()
        self.v = 0.0  # increments per second, signed

    def position(self, now):
        if self.v == 0:
            return self.p0
        p = self.p0 + self.v * (now - self.t0)
        if (self.v > 0 and p >= self.target) or (self.v < 0 and p <= self.target):
            return self.target
        return int(round(p))

    def moving(self, now):
        return self.position(now) != self.target

    def move(self, now, target, speed_inc_s):
        self.p0, self.t0, self.target = self.position(now), now, target
        self.v = 0.0 if target == self.p0 else (speed_inc_s if target > self.p0 else -speed_inc_s)

    def stop(self, now):
        self.move(now, self.position(now), 0.0)

    def write(self, regs):
        now = time.monotonic()
        b = b"".join(struct.pack("<H", r & 0xFFFF) for r in regs)
        ccon, cpos, _cdir, pct = b[0], b[1], b[2], b[3]
        (target,) = struct.unpack("<i", b[4:8])
        rising = lambda new, old, bit: (new & bit) and not (old & bit)
        self.enabled = bool(ccon & CCON_ENABLE)
        self.open = self.enabled and bool(ccon & CCON_STOP)
        self.halt = not (cpos & CPOS_HALT)
        if not self.open or self.halt:
            self.stop(now)
        if not cpos & (CPOS_START | CPOS_HOME):
            self.ack = False
        if self.open and not self.halt:
            if rising(cpos, self.prev_cpos, CPOS_HOME):
                self.referenced, self.pct, self.ack = True, 100, True
                self.move(now, 0, self.max_speed * self.inc_per_mm)
            elif rising(cpos, self.prev_cpos, CPOS_START) and self.referenced:
                self.pct, self.ack = pct, True
                self.move(now, target, self.max_speed * pct / 100.0 * self.inc_per_mm)
        self.prev_ccon, self.prev_cpos = ccon, cpos

    def read(self):
        now = time.monotonic()
        mov = self.moving(now)
        scon = SCON_VLOAD | SCON_DIRECT
        scon |= (SCON_ENABLED if self.enabled else 0) | (SCON_OPEN if self.open else 0)
        spos = (0 if self.halt else SPOS_HALT) | (SPOS_ACK if self.ack else 0)
        spos |= (SPOS_MOV if mov else SPOS_MC) | (SPOS_REF if self.referenced else 0)
        b = bytes([scon, spos, 0, self.pct if mov else 0]) + struct.pack("<i", self.position(now))
        return [b[2 * k] | b[2 * k + 1] << 8 for k in range(4)]


class FhppBlock(ModbusSequentialDataBlock):
    """Register 0..3: writes are the output telegram, reads the input telegram."""

    def __init__(self, drive):
        super().__init__(0, [0] * 4)
        self.drive = drive

    def validate(self, address, count=1):
        return address == 0 and 1 <= count <= 4

    def setValues(self, address, values):  # pylint: disable=invalid-name
        self.drive.write(list(values))

    def getValues(self, address, count=1):  # pylint: disable=invalid-name
        return self.drive.read()[:count]


async def main():
    logging.getLogger("pymodbus").setLevel(logging.CRITICAL)  # client hang-ups are routine
    inc_per_mm = float(sys.argv[1]) if len(sys.argv) > 1 else 1000.0
    max_speed = float(sys.argv[2]) if len(sys.argv) > 2 else 500.0
    block = FhppBlock(FhppDrive(inc_per_mm, max_speed))
    context = ModbusServerContext(slaves=ModbusSlaveContext(hr=block, zero_mode=True), single=True)
    server = ModbusTcpServer(context, address=("127.0.0.1", 0))
    task = asyncio.create_task(server.serve_forever())
    await server.serving
    print(f"PORT {server.server.sockets[0].getsockname()[1]}", flush=True)
    await asyncio.get_running_loop().run_in_executor(None, sys.stdin.read)
    await server.server_close()
    task.cancel()


if __name__ == "__main__":
    asyncio.run(main())
