#!/usr/bin/env python3
"""Drives the simulated printer with OctoPrint's own serial layer (octoprint.util.comm.MachineCom, OctoPrint
1.11 from PyPI, default settings) over the pty of `npm run sim -- --pty` (the firmware's own C++ as WebAssembly; its further arguments passed
on), as a user of OctoPrint would: connect,
temperatures, jogs refused before homing and past the bed's edge, home, a file whose F holds for the moves after
it, M84 after a move, stream a file, pause, resume, cancel, upload to the card, list it, print it from the card,
M112 and reconnect. Each step prints PASS or FAIL; a step
fails too if OctoPrint disconnected where a Marlin printer would have kept it connected. Prints
`N passed, N failed`."""
import logging
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
results = []


def wait(pred, seconds):
    end = time.time() + seconds
    while time.time() < end:
        if pred():
            return True
        time.sleep(0.05)
    return pred()


# --- OctoPrint without its web server: settings, an empty plugin system, events, the default profile ---------
basedir = tempfile.mkdtemp(prefix="octoprint-")
logging.basicConfig(level=logging.ERROR)
logging.getLogger("octoprint.printer.profile").setLevel(logging.CRITICAL)  # a fresh basedir makes its default profile
from octoprint import init_settings  # noqa: E402

init_settings(basedir, None)
import octoprint.plugin  # noqa: E402

octoprint.plugin.plugin_manager(init=True, plugin_folders=[], plugin_entry_points=[], plugin_disabled_list=[])
octoprint.plugin.plugin_manager().reload_plugins(startup=True, initialize_implementations=False)
from octoprint.events import eventManager  # noqa: E402

eventManager()
from octoprint.printer.profile import PrinterProfileManager  # noqa: E402
from octoprint.util import comm  # noqa: E402

profiles = PrinterProfileManager()


class Host(comm.MachineComPrintCallback):
    """What OctoPrint's printer object hears from its serial layer, kept for the checks. Like OctoPrint's own
    printer, it runs the afterPrintDone and afterPrintCancelled scripts (the latter sends M84)."""

    def __init__(self):
        self.lines, self.errors, self.events = [], [], []
        self.firmware = None
        self.temps = None
        self.custom = None
        self.sd_files = None
        self.com = None

    def on_comm_message(self, line):
        self.lines.append(line.strip())

    def on_comm_error(self, error, reason, consequence=None, faq=None, logs=None):
        self.errors.append(f"{reason}: {error}")

    def on_comm_firmware_info(self, name, data):
        self.firmware = name

    def on_comm_temperature_update(self, temp, bedTemp, chamberTemp, customTemp):
        self.temps, self.custom = dict(temp), dict(customTemp)

    def on_comm_sd_files(self, files):
        self.sd_files = [f[0] for f in files]

    def event(self, name):
        self.events.append(name)

    def on_comm_print_job_done(self, suppress_script=False):
        self.event("done")
        self.com.sendGcodeScript("afterPrintDone")

    def on_comm_print_job_cancelled(self, suppress_script=False, user=None):
        self.event("cancelled")
        self.com.sendGcodeScript("afterPrintCancelled")

    def on_comm_print_job_paused(self, suppress_script=False, user=None):
        self.event("paused")

    def on_comm_print_job_resumed(self, suppress_script=False, user=None):
        self.event("resumed")

    def on_comm_file_selected(self, filename, filesize, sd, user=None, data=None):
        self.event(f"selected {filename}")

    def on_comm_file_transfer_done(self, local_filename, remote_filename, elapsed):
        self.event(f"transferred {remote_filename}")

    def on_comm_file_transfer_failed(self, local_filename, remote_filename, elapsed):
        self.event(f"transfer failed {remote_filename}")


host = Host()


def check(name, ok, detail=""):
    """One step. It fails too if OctoPrint went offline or reported a firmware error meanwhile."""
    connected = host.com is not None and host.com.isOperational() and not host.errors
    ok = bool(ok) and (connected or name.startswith("M112"))
    results.append(ok)
    print(("PASS " if ok else "FAIL ") + name)
    if not ok:
        print(f"     {detail}; state {host.com.getStateString() if host.com else None}; errors {host.errors}")
        print("     last lines: " + " | ".join(host.lines[-12:]))


def run(*cmds, seconds=60):
    """Sends commands as OctoPrint's terminal does and returns the lines up to their end. OctoPrint keeps `ok`
    to itself and sends a line only after the one before was answered, so a closing `M113` (which echoes the
    busy interval) marks the end of everything before it."""
    start = len(host.lines)
    for c in cmds + ("M113",):
        host.com.sendCommand(c)
    ok = wait(lambda: any(l.startswith("echo:M113 S") for l in host.lines[start:]), seconds)
    lines = host.lines[start:]
    return lines[:next(i for i, l in enumerate(lines) if l.startswith("echo:M113 S"))] if ok else ["(no end)"] + lines


def jog(axis, mm):
    """OctoPrint's jog: relative, the move, back to absolute."""
    return run("G91", f"G1 {axis}{mm} F6000", "G90")


def position(settle=True):
    """Where the head is: after M400 (where it stopped), or at once. The last position line before the end marker."""
    lines = [l for l in run(*(("M400",) if settle else ()), "M114") if l.startswith("X:")]
    return lines[-1] if lines else ""


def connect(pty):
    host.errors.clear()
    host.firmware = None
    host.com = comm.MachineCom(pty, 115200, callbackObject=host, printerProfileManager=profiles)
    host.com.start()
    return wait(lambda: host.com.isOperational(), 20) and wait(lambda: host.firmware is not None, 10)


def gcode_file(name, lines):
    path = os.path.join(basedir, name)
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return path


def run_local(path):
    """Selects a file on the host and starts it, as OctoPrint's print button does."""
    host.com.selectFile(path, False)
    host.com.startPrint()
    return wait(lambda: host.com.isPrinting(), 10)


# Its own process group: npx starts node, and both must go when the test ends.
SPEED = 4  # the printer's seconds per wall-clock second
sim = subprocess.Popen(["npx", "tsx", "scripts/sim.ts", "--pty", "--speed", str(SPEED)] + sys.argv[1:], cwd=ROOT,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, start_new_session=True)
pty = None
for out in sim.stdout:
    m = re.match(r"pty (\S+)", out)
    if m:
        pty = m.group(1)
        break
threading.Thread(target=lambda: [None for _ in sim.stdout], daemon=True).start()  # keep its pipe drained
wait(lambda: pty and os.path.exists(pty), 10)

try:
    check("connects with default settings, firmware detected (M115)", connect(pty) and "UVExposure" in (host.firmware or ""),
          f"firmware {host.firmware}")
    check("the card is ready (M21: SD card ok)", wait(lambda: host.com.isSdReady(), 10))
    host.com.sendCommand("M105")
    ok = wait(lambda: host.temps and host.custom and len([k for k in host.custom if re.match(r"S[0-5]$", k)]) == 6, 15)
    check("temperatures: one tool and the six sensors as custom sensors, none with a target (no limit shown as one)",
          ok and list(host.temps.keys()) == [0] and host.temps[0][1] == 0.0
          and all(target in (None, 0.0) for _, target in host.custom.values()), f"tools {host.temps} custom {host.custom}")

    lines = jog("X", 10)
    check("a jog before homing is refused with echo:, and OctoPrint stays connected",
          any(l.startswith("echo:E14") for l in lines), lines)
    lines = run("G28", "M119")
    check("homes (G28)", "x_min: TRIGGERED" in lines and "y_min: TRIGGERED" in lines, lines)
    lines = jog("X", 500)
    check("a jog past the bed's edge is refused with echo:, the head stays",
          any(l.startswith("echo:E15") for l in lines) and position().startswith("X:0.000"), lines)

    # Marlin keeps a move's F for every later G0/G1. Set once, it holds for the 120 mm after it: 12 s at 10 mm/s,
    # where the travel speed (100 mm/s) would take 1.2 s. OctoPrint's own time only adds to what is measured.
    host.events.clear()
    start = time.time()
    started = run_local(gcode_file("feed.gcode", ["G90", "G1 X10 Y10 F600", "G1 X130 Y10", "M400"]))
    done = wait(lambda: "done" in host.events, 60)
    took = (time.time() - start) * SPEED
    check(f"a file's F holds for the moves after it: 10 mm then 120 mm at 10 mm/s took {took:.1f} s of the printer's time",
          started and done and took >= 12.0, f"started {started}, done {done}")

    run("G1 X150 Y150 F6000", "M84")
    at_release = position()
    check("M84 right after a move lets it end first: the head is where the move ended",
          at_release.startswith("X:150.000 Y:150.000"), f"M114 after M84 and M400: {at_release}")
    run("G28")

    path = gcode_file("stream.gcode", ["G90", "G1 X10 Y10 F6000", "G1 X150 Y120 F3000", "M400"])
    host.events.clear()
    started = run_local(path)
    done = wait(lambda: "done" in host.events, 60)
    at_done = position(settle=False) if done else ""  # no M400 of ours: the file's own must have waited
    check("streams a file; at its end (M400) the head is at the last move's end",
          started and done and at_done.startswith("X:150.000 Y:120.000"), f"M114 at the print's end: {at_done}")

    slow = ["G90"] + [f"G1 X{20 + 5 * (i % 2)} Y20 F3000\nG4 P300" for i in range(40)]
    host.events.clear()
    started = run_local(gcode_file("slow.gcode", slow))
    time.sleep(1)
    host.com.setPause(True)
    paused = wait(lambda: host.com.isPaused(), 10)
    host.com.setPause(False)
    resumed = wait(lambda: host.com.isPrinting() and "resumed" in host.events, 10)
    check("pauses and resumes a streamed file", started and paused and resumed, host.events)
    time.sleep(1)
    host.com.cancelPrint()
    cancelled = wait(lambda: "cancelled" in host.events and host.com.isOperational(), 20)
    time.sleep(1)  # the cancel script (M84, heaters off) runs
    check("cancels it; the cancel script's M84 and heater commands keep OctoPrint connected", cancelled, host.events)
    lines = jog("Y", 5)
    check("the jog after the cancel is refused (M84 un-homed the machine), still connected",
          any(l.startswith("echo:E14") for l in lines), lines)
    run("G28")

    card = ["G90", "G1 X30 Y40 F6000", "G4 P200", "G1 X60 Y40", "G1 X60 Y45"]
    host.events.clear()
    remote = host.com.startFileTransfer(gcode_file("card.gcode", card), "card.gcode")
    transferred = wait(lambda: any(e.startswith("transferred") for e in host.events), 60)
    check(f"uploads a G-code file to the card (M28 {remote} ... M29)", transferred and remote, host.events)
    host.com.refreshSdFiles(blocking=True)
    check("lists it (M20)", host.sd_files and remote in host.sd_files, f"{host.sd_files}")
    host.events.clear()
    host.com.selectFile(remote, True)
    selected = wait(lambda: any(e.startswith("selected") for e in host.events), 10)
    host.com.startPrint()
    sd_printing = wait(lambda: host.com.isSdPrinting(), 10)
    done = wait(lambda: "done" in host.events, 60)
    check("prints it from the card to Done printing file, progress from M27",
          selected and sd_printing and done and position().startswith("X:60.000 Y:45.000"), host.events)

    host.com.sendCommand("M112")
    check("M112: OctoPrint stops and closes the port", wait(lambda: host.com.isClosedOrError(), 10))
    host.com.close()
    time.sleep(1)
    check("reconnects after M112: the Mega was reset when the port opened (M115, M105 answer)",
          connect(pty) and any(l.startswith("T:") for l in run("M105")))
    lines = run("G28", "M119")
    check("and it homes again", "x_min: TRIGGERED" in lines, lines)
finally:
    if host.com:
        host.com.close()
    os.killpg(sim.pid, signal.SIGTERM)
    sim.wait(5)
    shutil.rmtree(basedir, ignore_errors=True)

passed = sum(results)
print(f"{passed} passed, {len(results) - passed} failed")
sys.exit(0 if all(results) and results else 1)
