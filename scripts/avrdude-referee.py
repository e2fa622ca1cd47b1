#!/usr/bin/env python3
"""avrdude as the referee of the bootloader rig: Debian's avrdude flashes and verifies each board through
the rig (scripts/rig_pty.py), as it would a board on /dev/ttyUSB0, and the firmware it wrote then answers.
This proves the rig is a board to a program that is not ours: it passes only if the bootloaders, fuses,
reset timing and pull-ups behave as avrdude expects of real ones. And the lock bits: an image reaching
into the Nano's 2 KB boot section must fail avrdude's verify, as on a real Nano.

  python3 scripts/avrdude-referee.py           the checks (npm test's stage), exit 1 on any failure
  python3 scripts/avrdude-referee.py --times   avrdude's time per board, as JSON (bench/flash.bench.ts)
"""

import json
import os
import re
import select
import subprocess
import sys
import termios
import time

from rig_pty import ROOT, RigPty

BOOT = os.path.join(ROOT, "build", "boot")
NANO_HEX = os.path.join(ROOT, "build", "avr", "nano.hex")
MEGA_HEX = os.path.join(ROOT, "build", "avr", "mega.hex")

# id, rig board, bootloader, avrdude's part and programmer, baud, image: as Arduino's IDE calls avrdude
# (platform.txt: -D for the Mega's wiring programmer, which has no chip erase).
BOARDS = [
    ("nano", "nano", "optiboot_atmega328.hex", "m328p", "arduino", 115200, NANO_HEX, []),
    ("nano-old", "nano", "atmegaboot_atmega328.hex", "m328p", "arduino", 57600, NANO_HEX, []),
    ("mega", "mega", "stk500v2_atmega2560.hex", "m2560", "wiring", 115200, MEGA_HEX, ["-D"]),
]


def avrdude(port, part, programmer, baud, hex_path, extra):
    args = ["avrdude", "-q", "-p", part, "-c", programmer, "-P", port, "-b", str(baud), *extra, "-U", f"flash:w:{hex_path}:i"]
    t0 = time.time()
    run = subprocess.run(args, capture_output=True, text=True, timeout=300)
    # A pty has no modem lines: avrdude's DTR ioctls fail there, and the bridge resets on open instead.
    log = "\n".join(l for l in run.stderr.splitlines() if "TIOCMGET" not in l)
    return run.returncode, time.time() - t0, log


def ask(port, board_id, seconds=8):
    """Opens the port at 115200 as a terminal would (which resets the board) and asks the firmware who it is."""
    fd = os.open(port, os.O_RDWR | os.O_NOCTTY)
    try:
        attrs = termios.tcgetattr(fd)
        attrs[0] = attrs[1] = attrs[3] = 0
        attrs[2] = termios.CS8 | termios.CREAD | termios.CLOCAL
        attrs[4] = attrs[5] = termios.B115200
        termios.tcsetattr(fd, termios.TCSANOW, attrs)
        heard = b""
        until = time.time() + seconds
        asked = 0.0
        while time.time() < until:
            started = b"start" in heard
            if (board_id != "mega" or started) and time.time() - asked > 0.5:
                os.write(fd, b"M115\n" if board_id == "mega" else b"V\n")
                asked = time.time()
            if select.select([fd], [], [], 0.05)[0]:
                heard += os.read(fd, 4096)
            if re.search(rb"FIRMWARE_NAME:[^\n]*\n|V:\d+,[^\n]*\n", heard) and until - time.time() > 1.5:
                until = time.time() + 1.5  # and a while longer: a halt would follow the answer
        return heard.decode("latin1")
    finally:
        os.close(fd)


def flash_one(board_id, rig_board, boot, part, programmer, baud, hex_path, extra):
    rig = RigPty(rig_board, os.path.join(BOOT, boot))
    try:
        rc, seconds, log = avrdude(rig.path, part, programmer, baud, hex_path, extra)
        # Asked twice, each open a reset: the second start must find its pull-ups as the first did.
        answer = ask(rig.path, board_id) + ask(rig.path, board_id) if rc == 0 else ""
        return rc, seconds, log, answer
    finally:
        rig.close()


def reaching_into_boot_section(path):
    """The Nano image with 16 bytes more at 0x78F0: the second page past 30720, in the locked boot section."""
    with open(path) as f:
        lines = [l.strip() for l in f if l.startswith(":")]
    record = bytes([16, 0x78, 0xF0, 0]) + bytes(range(16))
    record += bytes([(-sum(record)) & 0xFF])
    out = os.path.join(ROOT, "build", "avr", "nano-into-boot-section.hex")
    with open(out, "w") as f:
        f.write("\n".join(lines[:-1] + [":" + record.hex().upper(), lines[-1]]) + "\n")
    return out


def main():
    failures = 0
    times = {}
    for board in BOARDS:
        board_id = board[0]
        rc, seconds, log, answer = flash_one(*board)
        if "--times" in sys.argv and rc != 0 and "initialization failed" in log:
            # Timing only: on a loaded machine the rig can answer a sync later than avrdude's 250 ms
            # drain expects, and avrdude gives up before writing. Timed again, and said so.
            print(f"{board_id}: avrdude did not get in sync; timed on a second try", file=sys.stderr)
            rc, seconds, log, answer = flash_one(*board)
        times[board_id] = round(seconds, 2)
        if "--times" in sys.argv:
            if rc != 0:
                print(log, file=sys.stderr)
                return 1
            continue
        ok = rc == 0 and "bytes of flash verified" in log
        version = re.search(r"FIRMWARE_NAME:.*? PROTOCOL|V:\d+,\S+", answer)
        halted = "halted" in answer or "E13" in answer
        print(f"{'PASS' if ok else 'FAIL'}  avrdude -c {board[4]} -b {board[5]} flashed and verified the {board_id} ({seconds:.1f} s)")
        if not ok:
            print(log)
        print(f"{'PASS' if version and not halted else 'FAIL'}  the firmware avrdude wrote answers {version.group(0) if version else repr(answer[-200:])}{' but is halted' if halted else ''}")
        failures += (not ok) + (not version or halted)
    if "--times" in sys.argv:
        print(json.dumps(times))
        return 0

    # The lock bits: two pages past boards.txt's 30720 B land in the boot section, which SPM may not write.
    image = reaching_into_boot_section(NANO_HEX)
    rig = RigPty("nano", os.path.join(BOOT, "optiboot_atmega328.hex"))
    try:
        rc, _, log = avrdude(rig.path, "m328p", "arduino", 115200, image, [])
    finally:
        rig.close()
    refused = rc != 0 and re.search(r"verification error|mismatch", log, re.I) and re.search(r"0x78[0-9a-f]{2}", log)
    print(f"{'PASS' if refused else 'FAIL'}  an image with 16 B at 0x78F0, past 30720, fails avrdude's verify there: the locked boot section")
    if not refused:
        print(log)
    failures += not refused
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
