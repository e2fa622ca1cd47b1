#!/usr/bin/env bash
# Installs the Debian packages the tests need when they are missing (as root), or says exactly what to install.
set -euo pipefail

PACKAGES=(
  chromium                                  # Playwright's browser (its own download is not used)
  gcc-avr avr-libc arduino-core-avr         # AVR images of the Nano and Mega firmware
  cmake g++ libgtest-dev nlohmann-json3-dev # C++ host tests
  clang                                     # the sanitizer builds and libFuzzer (scripts/fuzz.sh, tsan.sh)
  lld wasi-libc libc++-dev-wasm32 libclang-rt-dev-wasm32  # the firmware's cores as WebAssembly (scripts/build-wasm.sh)
  libboost-dev                              # the ESP hub on the host: HTTP and WebSocket (Boost.Beast)
  simavr libsimavr-dev libelf-dev           # running the AVR images in simulation
  avrdude                                   # the referee of the bootloader rig (scripts/avrdude-referee.py)
  python3 python3-venv                      # vector authoring, the vector-binding check, printcore's venv
  socat                                     # `npm run sim -- --pty`
  gerbv                                     # Gerber import: reference rasters of its example boards (app/src/pcb)
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if ((${#missing[@]} == 0)); then
  exit 0
fi
if [[ $(id -u) -ne 0 ]]; then
  echo "Missing system packages. Install them with:" >&2
  echo "  sudo apt-get update && sudo apt-get install -y ${missing[*]}" >&2
  exit 1
fi
echo "Installing system packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq "${missing[@]}" >/dev/null
