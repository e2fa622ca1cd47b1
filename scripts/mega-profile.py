#!/usr/bin/env python3
"""Names the functions of a profile of the real Mega image in simavr: the cycles each function took
(its own instructions, not its callees'), the most first, and how often it was entered (runs of its
first instruction; a loop back to it counts too). The profile comes from the rig
(firmware/mega/test/sim/board_sim.h, megaProfile), for example the photo-like scan pass:

  UV_MEGA_PROFILE=/tmp/mega.prof build/host/mega_sim_tests --gtest_filter='*/ScanBoardTest.APhotoLikePass*'
  python3 scripts/mega-profile.py /tmp/mega.prof [build/avr/mega.elf] [rows]
"""
import bisect
import subprocess
import sys


def symbols(elf):
    """(start, end, name) of every sized function in the image's text, by start."""
    out = subprocess.run(["avr-nm", "-S", "-C", "--defined-only", elf], capture_output=True, text=True, check=True).stdout
    funcs = []
    for line in out.splitlines():
        parts = line.split(maxsplit=3)
        if len(parts) == 4 and parts[2] in "tTwW":
            start, size = int(parts[0], 16), int(parts[1], 16)
            if start < 0x800000:  # text, not data (avr-nm puts RAM at 0x800000)
                funcs.append((start, start + size, parts[3]))
    return sorted(funcs)


def main():
    prof = sys.argv[1]
    elf = sys.argv[2] if len(sys.argv) > 2 else "build/avr/mega.elf"
    rows = int(sys.argv[3]) if len(sys.argv) > 3 else 30
    funcs = symbols(elf)
    starts = [f[0] for f in funcs]
    by = {}
    total = 0
    entered = {}
    for line in open(prof):
        addr, cycles, runs = line.split()
        addr, cycles = int(addr, 16), int(cycles)
        total += cycles
        i = bisect.bisect_right(starts, addr) - 1
        name = funcs[i][2] if i >= 0 and addr < funcs[i][1] else f"?{addr:05x}"
        by[name] = by.get(name, 0) + cycles
        if i >= 0 and addr == funcs[i][0]:
            entered[name] = entered.get(name, 0) + int(runs)
    print(f"{total} cycles ({total / 16e3:.1f} ms at 16 MHz) in {len(by)} functions")
    for name, cycles in sorted(by.items(), key=lambda kv: -kv[1])[:rows]:
        n = entered.get(name, 0)
        each = f"{cycles / n / 16:8.1f} us" if n else " " * 11
        print(f"{100 * cycles / total:6.2f} %  {cycles / 16e3:9.2f} ms  {n:8d} x {each}  {name[:100]}")


if __name__ == "__main__":
    main()
