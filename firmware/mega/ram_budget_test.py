# Tests ram_budget.py, the post-action that makes `pio run` fail over the Mega's static-RAM budget:
# its parsing of avr-size, its verdict, and the action as PlatformIO would call it (a fake env and a
# fake size tool); and link_flags.py, the pre-script that puts the section flags on the link line.
# Run by scripts/build-avr.sh: python3 firmware/mega/ram_budget_test.py
import contextlib
import io
import os
import stat
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ram_budget  # noqa: E402

SIZE_A = """firmware.elf  :
section                      size      addr
.data                         276   8389120
.text                      103492         0
.bss                         4501   8389396
.comment                       17         0
.note.gnu.avr.deviceinfo       64         0
Total                      108350
"""


class FakeBoard:
    def __init__(self, budget):
        self.budget = budget

    def get(self, key, default):
        return self.budget if key == "upload.maximum_ram_size" else default


class FakeEnv:
    """What the action uses of PlatformIO's SCons environment."""

    def __init__(self, tool, budget):
        self.tool, self.board, self.actions, self.exit_code = tool, FakeBoard(budget), [], None
        self.vars = {"ENV": {"PATH": os.environ["PATH"]}}

    def __getitem__(self, key):
        return self.vars[key]

    def subst(self, text):
        return self.tool if text == "$SIZETOOL" else text

    def BoardConfig(self):
        return self.board

    def AddPostAction(self, target, action):
        self.actions.append((target, action))

    def Exit(self, code):
        self.exit_code = code


class RamBudget(unittest.TestCase):
    def test_static_ram_is_data_plus_bss(self):
        self.assertEqual(ram_budget.static_ram(SIZE_A), 276 + 4501)
        self.assertEqual(ram_budget.static_ram(SIZE_A + ".noinit 10 0\n"), 276 + 4501 + 10)

    def test_output_without_the_sections_is_an_error_not_zero(self):
        with self.assertRaises(ValueError):
            ram_budget.static_ram("firmware.elf  :\nsection size addr\n.text 100 0\n")

    def test_verdict_at_over_and_without_a_budget(self):
        self.assertTrue(ram_budget.verdict(4915, 4915)[0])
        ok, line = ram_budget.verdict(4916, 4915)
        self.assertFalse(ok)
        self.assertIn("over budget by 1 bytes", line)
        self.assertFalse(ram_budget.verdict(100, 0)[0])

    def run_action(self, budget):
        with tempfile.TemporaryDirectory() as d:
            tool = os.path.join(d, "avr-size")
            with open(tool, "w") as f:
                f.write("#!/bin/sh\n[ \"$1 $2\" = '-A -d' ] || exit 2\ncat <<'END'\n" + SIZE_A + "END\n")
            os.chmod(tool, os.stat(tool).st_mode | stat.S_IXUSR)
            env = FakeEnv(tool, budget)
            ram_budget.register(env)
            self.assertEqual(len(env.actions), 1)
            target, action = env.actions[0]
            self.assertEqual(target, "$PROGPATH")
            printed = io.StringIO()
            with contextlib.redirect_stdout(printed), contextlib.redirect_stderr(printed):
                action([], [os.path.join(d, "firmware.elf")], env)
            self.assertIn("Static RAM: 4777 of %d bytes" % budget, printed.getvalue())
            return env.exit_code

    def test_the_post_action_fails_the_build_over_budget_and_passes_within_it(self):
        self.assertEqual(self.run_action(4776), 1)
        self.assertIsNone(self.run_action(4777))


class LinkFlagsTest(unittest.TestCase):
    def test_the_section_flags_go_on_the_link_line(self):
        class Env:
            def __init__(self):
                self.flags = {}

            def Append(self, **kw):
                for k, v in kw.items():
                    self.flags.setdefault(k, []).extend(v)

        env = Env()
        path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "link_flags.py")
        with open(path) as f:
            exec(compile(f.read(), path, "exec"), {"Import": lambda name: None, "env": env})
        self.assertEqual(env.flags, {"LINKFLAGS": ["-ffunction-sections", "-fdata-sections"]})


if __name__ == "__main__":
    unittest.main()
