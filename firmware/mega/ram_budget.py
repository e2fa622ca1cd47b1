# `pio run`'s static-RAM check for the Mega: PlatformIO 6 only warns when .data + .bss exceed
# board_upload.maximum_ram_size (it fails only for flash), so this post-action on the firmware ELF
# fails the build instead. Plain functions, so ram_budget_test.py runs them without PlatformIO.
import os
import re
import subprocess
import sys

SECTIONS = re.compile(r"^(\.data|\.bss|\.noinit)\s+(\d+)")


def static_ram(size_output):
    """Bytes of static RAM (.data + .bss + .noinit) in `avr-size -A -d` output."""
    sizes = [int(m.group(2)) for m in map(SECTIONS.match, size_output.splitlines()) if m]
    if not sizes:
        raise ValueError("no .data or .bss in the size tool's output")
    return sum(sizes)


def verdict(used, budget):
    """(within budget, the line to print). A budget of 0 means the board set none: that fails too,
    since the check would otherwise pass silently."""
    if budget <= 0:
        return False, "Error: board_upload.maximum_ram_size is not set: no static-RAM budget to check"
    line = "Static RAM: %d of %d bytes allowed (.data + .bss)" % (used, budget)
    if used > budget:
        return False, "Error: static RAM over budget by %d bytes. %s" % (used - budget, line)
    return True, "%s, %d to spare" % (line, budget - used)


def check(elf, size_tool, budget, path=None):
    """Runs the size tool on the ELF; returns verdict()'s pair."""
    env = dict(os.environ)
    if path:
        env["PATH"] = path
    out = subprocess.run([size_tool, "-A", "-d", elf], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         universal_newlines=True, env=env, check=True).stdout
    return verdict(static_ram(out), budget)


def register(env):
    """Attaches the check to the program ELF (PlatformIO's Pre & Post Actions: env.AddPostAction on
    $PROGPATH), using the platform's $SIZETOOL and the PATH PlatformIO gives its tools."""

    def check_static_ram(source, target, env):
        ok, line = check(str(target[0]), env.subst("$SIZETOOL"),
                         int(env.BoardConfig().get("upload.maximum_ram_size", 0)), str(env["ENV"]["PATH"]))
        (sys.stdout if ok else sys.stderr).write(line + "\n")
        if not ok:
            env.Exit(1)

    env.AddPostAction("$PROGPATH", check_static_ram)


try:
    Import("env")  # noqa: F821 (SCons defines Import when PlatformIO runs this as an extra script)
except NameError:
    pass  # imported by the test
else:
    register(env)  # noqa: F821
