"""The bootloader rig (build/host/bootloader_rig) behind a pseudo-terminal, for programs that open a
serial port: avrdude (scripts/avrdude-referee.py) and anything else that speaks to a board by its device.

A pty carries no modem lines, so DTR cannot be pulsed through it. What a USB serial chip does when a
program opens its port, it does here: DTR goes up, and the board resets. The bridge sees the open as the
master's hang-up clearing, and sends the rig the port's baud (read off the pty's termios) and a reset.
"""

import os
import pty
import select
import struct
import subprocess
import termios
import threading
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RIG = os.path.join(ROOT, "build", "host", "bootloader_rig")

BAUDS = {getattr(termios, f"B{b}"): b for b in (9600, 19200, 38400, 57600, 115200, 230400, 460800)}


class RigPty:
    """One board on a pty: `path` is the device to open, as /dev/ttyUSB0 would be."""

    def __init__(self, board, boot_hex, app_hex=None):
        args = [RIG, "--board", board, "--boot", boot_hex] + (["--app", app_hex] if app_hex else [])
        self.rig = subprocess.Popen(args, stdin=subprocess.PIPE, stdout=subprocess.PIPE)
        self.master, slave = pty.openpty()
        self.path = os.ttyname(slave)
        os.close(slave)  # no one holds the port open: the master hangs up until a program opens it
        self.opens = 0
        self._stop = False
        self._thread = threading.Thread(target=self._bridge, daemon=True)
        self._thread.start()

    def _send(self, frame):
        self.rig.stdin.write(frame)
        self.rig.stdin.flush()

    def _baud(self):
        return BAUDS.get(termios.tcgetattr(self.master)[5], 0)

    def _bridge(self):
        is_open = False
        baud = 0
        rig_out = self.rig.stdout.fileno()
        while not self._stop:
            hung_up = self._hung_up()
            if not hung_up and not is_open:
                is_open = True
                self.opens += 1
                baud = self._baud()
                self._send(b"B" + struct.pack("<I", baud) + b"R")  # opened: DTR up, the board resets
            elif hung_up and is_open:
                is_open = False
            if is_open and self._baud() != baud:  # the program set the port's speed after opening it
                baud = self._baud()
                self._send(b"B" + struct.pack("<I", baud))
            ready, _, _ = select.select([rig_out] + ([self.master] if is_open else []), [], [], 0.002 if is_open else 0.01)
            if rig_out in ready:
                data = os.read(rig_out, 4096)
                if not data:
                    return
                if is_open:
                    try:
                        os.write(self.master, data)
                    except OSError:
                        pass
            if self.master in ready:
                try:
                    data = os.read(self.master, 255)
                except OSError:
                    continue
                if data:
                    self._send(b"D" + bytes([len(data)]) + data)

    def _hung_up(self):
        p = select.poll()
        p.register(self.master, select.POLLIN | select.POLLHUP)
        return any(ev & select.POLLHUP for _, ev in p.poll(0))

    def close(self):
        self._stop = True
        self._thread.join(timeout=1)
        self.rig.kill()
        self.rig.wait()
        os.close(self.master)


def wait_for(predicate, seconds):
    until = time.time() + seconds
    while time.time() < until:
        if predicate():
            return True
        time.sleep(0.01)
    return False
