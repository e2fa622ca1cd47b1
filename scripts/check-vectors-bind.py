#!/usr/bin/env python3
"""Proves the protocol vectors bind both implementations: for every section of every vector
file, change one expected byte in a copy and check that the TypeScript suite AND the C++
suite both fail on it, or the C++ suite alone for a section only the firmware reads (FIRMWARE_ONLY).
Usage: check-vectors-bind.py <host build dir with protocol_tests and esp_tests>"""
import json
import os
import random
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
VECTORS = os.path.join(ROOT, "protocol", "vectors")
# The field that holds the expected bytes in each section (or a list of such fields, each checked).
EXPECTED = {
    "nano.json": {"commands": "line", "parseOnly": "line", "replies": "line", "streams": "lines"},
    "mega.json": {"frames": "frame", "frameErrors": "error", "commands": "command", "sessions": "steps",
                  "replies": "reply"},
    "job.json": {"jobs": "text", "invalid": "error"},
    "esp.json": {"requests": ["text", "paced"]},
    "planner-cpp.json": {"cases": "plan"},
    "mesh.json": {"cases": "points"},
    "scan-cpp.json": {"cases": "scan"},
    "mixed-cpp.json": {"cases": "mixed"},
    "nano-program.json": {"programs": "lines", "sessions": "steps"},
}
# The C++ test program that reads each file (a list: each of them must fail).
CXX_BINARY = {"nano.json": "protocol_tests", "mega.json": "protocol_tests", "job.json": "protocol_tests",
              "esp.json": "esp_tests", "planner-cpp.json": "planner_tests",
              "mesh.json": "planner_tests", "scan-cpp.json": "planner_tests",
              "mixed-cpp.json": "planner_tests",
              "nano-program.json": "protocol_tests", "nano-program.json#sessions": "nano_tests",
              # The jobs' texts bind the ESP hub's path too (hub_job_format_test.cpp): each must fail.
              "job.json#jobs": ["protocol_tests", "esp_tests"]}
# Sections that only the firmware implements: the Nano's program store runs in C++ alone since the
# simulated printer became the firmware's C++ (issue 27); there is no TypeScript Nano to bind. Nor a
# TypeScript Mega to take lines (issue 38): the sessions of mega.json bind the Mega's line receiver.
# Nor a TypeScript reader of job text or writer of scan programs: the app writes jobs (job.json#jobs
# binds its encoder) and the Mega reads them and writes the Nano's program lines. Nor a TypeScript
# codec of the printhead link, which the app never speaks (issue 38): nano.json binds the C++ alone.
# Nor a TypeScript reader of frames or commands: the Mega parses them. The app writes frames, and
# checks the canonical ones of mega.json#frames by encoding them, but a mutation may fall on a frame
# only the Mega reads, so that section binds the C++ alone too. The app reads replies: mega.json#replies
# binds both. Nor a TypeScript hub: the end-to-end tests run the ESP's own C++ on the host, so
# esp.json binds the hub's C++ alone.
FIRMWARE_ONLY = {"esp.json#requests", "nano-program.json#sessions", "mega.json#sessions", "job.json#invalid", "nano-program.json#programs",
                 "nano.json#commands", "nano.json#parseOnly", "nano.json#replies", "nano.json#streams",
                 "mega.json#frames", "mega.json#frameErrors", "mega.json#commands"}


def mutate(value, rng):
    """Changes one byte (or number) somewhere inside an expected value."""
    if isinstance(value, str):
        i = rng.randrange(len(value))
        ch = value[i]
        new = "0" if ch != "0" else "1"
        if ch.isalpha():
            new = "x" if ch != "x" else "y"
        return value[:i] + new + value[i + 1:]
    if isinstance(value, bool):
        return not value
    if isinstance(value, int):
        return value + 1
    if isinstance(value, list):
        value = list(value)
        if not value:
            return ["x"]
        i = rng.randrange(len(value))
        value[i] = mutate(value[i], rng)
        return value
    if isinstance(value, dict):
        value = dict(value)
        k = rng.choice(sorted(value))
        value[k] = mutate(value[k], rng)
        return value
    return "x"


def ts_readers(file):
    """The TypeScript test files that read a vector file (each names it): running only these keeps
    the check to minutes instead of the whole suite per mutation."""
    out = subprocess.run(["grep", "-rl", "--include=*.test.ts", file, "app/src"], cwd=ROOT, capture_output=True, text=True).stdout.split()
    return sorted(out) or ["app/src"]


def fails(cmd, env):
    return subprocess.run(cmd, env=env, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode != 0


def main():
    build = sys.argv[1]
    rng = random.Random(20261121)
    checked, problems = 0, []
    for file, sections in EXPECTED.items():
        original = json.load(open(os.path.join(VECTORS, file)))
        pairs = [(s, f) for s, fs in sections.items() for f in (fs if isinstance(fs, list) else [fs])]
        for section, field in pairs:
            cases = [c for c in original[section] if field in c]
            case = rng.choice(cases)
            with tempfile.TemporaryDirectory() as tmp:
                for f in os.listdir(VECTORS):
                    shutil.copy(os.path.join(VECTORS, f), tmp)
                doc = json.loads(json.dumps(original))
                target = doc[section][original[section].index(case)]
                if field == "points":  # [x, y, expected z]: change the expectation, not the input
                    point = rng.choice(target[field])
                    point[2] += 1
                elif field == "steps":  # a session's steps: change what a step expects, not what it sends
                    step = rng.choice([st for st in target[field] if "reply" in st or "execute" in st])
                    key = "reply" if "reply" in step else "execute"
                    step[key] = mutate(step[key], rng)
                else:
                    target[field] = mutate(target[field], rng)
                json.dump(doc, open(os.path.join(tmp, file), "w"))
                env = dict(os.environ, UV_VECTORS_DIR=tmp)
                only_cc = f"{file}#{section}" in FIRMWARE_ONLY
                ts = only_cc or fails(["npx", "vitest", "run", *ts_readers(file), "--reporter=dot"], env)
                binaries = CXX_BINARY.get(f"{file}#{section}", CXX_BINARY[file])
                cc = all(fails([os.path.join(build, b)], env) for b in (binaries if isinstance(binaries, list) else [binaries]))
                checked += 1
                verdict = ("the firmware fails" if only_cc else "both fail") if ts and cc else f"NOT CAUGHT (ts failed={ts}, c++ failed={cc})"
                print(f"  {file} {section}.{field}: {verdict}")
                if not (ts and cc):
                    problems.append(f"{file} {section}.{field}")
    print(f"{checked - len(problems)} passed, {len(problems)} failed")
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
