#!/usr/bin/env python3
"""Drives the simulated printer with a real desktop host: printcore from Printrun, over the pty of
`npm run sim -- --pty`, as Pronterface would. It connects, homes, moves, reads temperatures, and streams
an exposure job as a print (numbered, checksummed lines), then exposes it. Prints `N passed, N failed`."""
import json
import os
import re
import signal
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
from printrun import gcoder  # noqa: E402
from printrun.printcore import printcore  # noqa: E402

results = []


def check(name, ok, detail=""):
    results.append(ok)
    print(("PASS " if ok else "FAIL ") + name + ("" if ok else f": {detail}"))


def wait(pred, seconds):
    end = time.time() + seconds
    while time.time() < end:
        if pred():
            return True
        time.sleep(0.05)
    return pred()


# Its own process group: npx starts node, and both must go when the test ends.
sim = subprocess.Popen(["npx", "tsx", "scripts/sim.ts", "--pty", "--speed", "20"] + sys.argv[1:], cwd=ROOT,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, start_new_session=True)
pty = None
for line in sim.stdout:
    m = re.match(r"pty (\S+)", line)
    if m:
        pty = m.group(1)
        break
wait(lambda: pty and os.path.exists(pty), 10)

received = []
sent = []
p = printcore()
p.recvcb = lambda l: received.append(l.strip())
p.sendcb = lambda command, *_: sent.append(command)  # printcore empties p.sent when a print ends
try:
    p.connect(pty, 115200)
    check("connects over the pty", wait(lambda: p.online, 15), "printcore never came online")

    def reply(cmd, pattern, seconds=30):
        start = len(received)
        p.send_now(cmd)
        ok = wait(lambda: any(re.search(pattern, l) for l in received[start:]), seconds)
        return ok, [l for l in received[start:] if re.search(pattern, l)]

    ok, _ = reply("G28", r"^ok")
    check("homes (G28)", ok)
    p.send_now("G0 X12.5 Y30 F6000")
    moved = False
    for _ in range(60):  # the move takes a while; ask until the head is there
        moved, lines = reply("M114", r"^X:", 5)
        moved = moved and lines[-1].startswith("X:12.500 Y:30.000")
        if moved:
            break
        time.sleep(0.1)
    check("moves and reports the position (G0, M114)", moved, received[-3:])
    ok, lines = reply("M105", r"^T:\d+\.\d /0\.0 S0:")
    check("reads six temperatures (M105)", ok, lines)

    job = json.load(open(os.path.join(ROOT, "protocol", "vectors", "job.json")))["jobs"][0]["text"]
    records = job.strip().split("\n")
    gcode = gcoder.LightGCode(["M28 PRINTCORE.UVJ"] + records + ["M29"])
    errors_before = len([l for l in received if l.startswith("Error")])
    p.startprint(gcode)
    done = wait(lambda: not p.printing, 60)
    check("streams the job with line numbers and checksums", done and any("Done saving file." in l for l in received),
          received[-10:])
    numbered = [s for s in sent if re.match(r"^N\d+ r \d+ \d+ [0-9a-f]+\*\d+$", s)]
    check("every record went out numbered and checksummed", len(numbered) == len([r for r in records if r.startswith("r ")]), sent[-5:])
    check("no errors during the print", len([l for l in received if l.startswith("Error")]) == errors_before, received[-10:])
    ok, lines = reply("M20", r"^PRINTCORE\.UVJ \d+$")
    check("the job is on the SD card, byte for byte", ok and lines[0] == f"PRINTCORE.UVJ {len(job)}", lines)
    # A job in format 2 (job.md "Run-length rows") goes the same way: its `rl` lines are job records too.
    job2 = next(j for j in json.load(open(os.path.join(ROOT, "protocol", "vectors", "job.json")))["jobs"] if j.get("format") == 2)["text"]
    records2 = job2.strip().split("\n")
    saved = len([l for l in received if "Done saving file." in l])
    p.startprint(gcoder.LightGCode(["M28 PRINTCORE2.UVJ"] + records2 + ["M29"]))
    done = wait(lambda: not p.printing and len([l for l in received if "Done saving file." in l]) > saved, 60)
    check("streams a format 2 job (run-length rows) and the Mega verifies it", done, received[-10:])
    ok, lines = reply("M20", r"^PRINTCORE2\.UVJ \d+$")
    check("the format 2 job is on the SD card, byte for byte", ok and lines[0] == f"PRINTCORE2.UVJ {len(job2)}", lines)
    p.send_now("M23 PRINTCORE.UVJ")
    ok, lines = reply("M24", r"^JOB:(running|done)")
    check("exposes it (M23, M24)", ok, received[-5:])
finally:
    p.disconnect()
    os.killpg(sim.pid, signal.SIGTERM)
    sim.wait(5)

passed = sum(results)
print(f"{passed} passed, {len(results) - passed} failed")
sys.exit(0 if all(results) and results else 1)
