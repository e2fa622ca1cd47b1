#!/usr/bin/env bash
# Runs every test of the project: the README's test command. Each stage runs even if an earlier one
# failed; a summary closes the run and the exit code is non-zero if anything failed.
set -uo pipefail
cd "$(dirname "$0")/.."
export PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1

bash scripts/system-deps.sh || exit 1
[[ -d node_modules ]] || npm ci

results=()
failed=0

stage() {
  local name=$1
  shift
  echo
  echo "=== $name"
  local start=$SECONDS
  if "$@"; then
    results+=("PASS  $name ($((SECONDS - start)) s)")
  else
    results+=("FAIL  $name ($((SECONDS - start)) s)")
    failed=$((failed + 1))
  fi
}

stage "The simulated printer's module (printer.wasm) is what the firmware's sources build, byte for byte" bash scripts/build-wasm.sh --check
stage "The planner's module (planner.wasm) is what the planner's sources build, byte for byte" bash scripts/build-planner-wasm.sh --check
# The AVR images first: Vitest reads them too (the flasher's chip and HEX checks on the real images).
stage "AVR firmware images and budgets" bash scripts/test-firmware.sh images
stage "TypeScript unit tests (Vitest)" npm run --silent test:unit
stage "Type check (svelte-check)" npm run --silent check
stage "C++ host and simavr tests (CMake, GoogleTest)" bash scripts/test-firmware.sh host
stage "avrdude flashes and verifies each board through the bootloader rig (the rig's referee)" bash scripts/test-firmware.sh avrdude
stage "C++ tests under ASan and UBSan (clang)" bash scripts/fuzz.sh --tests
stage "The ESP's hand-over between two threads under ThreadSanitizer (clang)" bash scripts/tsan.sh
stage "Fuzzers, 20 s each on their seeds and grown corpus (libFuzzer, ASan, UBSan)" bash scripts/fuzz.sh 20
stage "The app for the ESP's flash (gzipped, within its budget)" npm run --silent build:esp
stage "Vectors bind both implementations" python3 scripts/check-vectors-bind.py build/host
printcore_test() {
  [[ -x build/venv/bin/python ]] || python3 -m venv build/venv || return 1
  build/venv/bin/python -c 'import printrun' 2>/dev/null ||
    build/venv/bin/pip install -q --no-deps Printrun pyserial appdirs || return 1
  # The firmware's own C++ (as WebAssembly) behind the pty: what a host meets on the machine.
  build/venv/bin/python scripts/sim-printcore-test.py 2>&1 | grep -v '^WARNING'
  return "${PIPESTATUS[0]}"
}

octoprint_test() {
  # OctoPrint's own serial layer, from PyPI, in a venv of its own on Python 3.11 (../shared/TOOLCHAIN.md).
  local python
  python=$(command -v python3.11 || command -v python3)
  [[ -x build/octoprint-venv/bin/python ]] || "$python" -m venv build/octoprint-venv || return 1
  build/octoprint-venv/bin/python -c 'import octoprint' 2>/dev/null ||
    build/octoprint-venv/bin/pip install -q OctoPrint==1.11.8 || return 1
  build/octoprint-venv/bin/python scripts/sim-octoprint-test.py
}

stage "Desktop host: printcore over the firmware's C++ (WebAssembly) on a pty" printcore_test
stage "Desktop host: OctoPrint 1.11 (MachineCom, default settings) over the firmware's C++ (WebAssembly) on a pty" octoprint_test
stage "End-to-end in Chromium (Playwright)" npx playwright test

echo
echo "=== Summary"
printf '%s\n' "${results[@]}"
echo "stages: $((${#results[@]} - failed)) passed, $failed failed"
((failed == 0))
