#!/usr/bin/env bash
# The firmware's tests alone (npm run test:firmware), as npm test runs them: `images` builds the AVR
# images and checks their budgets, `host` runs the C++ host tests and the simavr runs of those images
# with the figures they measure, `avrdude` has avrdude flash every board through the bootloader rig;
# no argument runs images and host. System packages: scripts/system-deps.sh.
set -uo pipefail
cd "$(dirname "$0")/.."

images() {
  bash scripts/build-avr.sh &&
    bash scripts/build-bootloaders.sh  # the real bootloaders, from Debian's sources, for the flasher's rig
}

host() {
  # ctest runs the quick suites; the ones whose measurements belong in the log run here, their
  # figures printed (a failure still fails the stage: pipefail).
  cmake -S firmware -B build/host -DCMAKE_BUILD_TYPE=Debug >/dev/null &&
    cmake --build build/host -j"$(nproc)" >/dev/null &&
    (cd build/host && ctest --output-on-failure -E '^(nano_sim_tests|mega_sim_tests|mega_tests)$') &&
    build/host/nano_sim_tests --gtest_brief=1 | grep '^\[nano budget\]' &&
    build/host/mega_sim_tests --gtest_brief=1 | grep -E '^\[(mega budget|stop cycle)\]|FAILED|Failure' &&
    build/host/mega_tests --gtest_brief=1 | grep -E '^\[mega |FAILED|Failure' &&
    { build/host/protocol_tests --gtest_brief=1 && build/host/esp_tests --gtest_brief=1; } | grep -E '^\[(vectors|esp )\]|^\[esp |FAILED|Failure'
}

avrdude_referee() {
  # Debian's avrdude flashes and verifies every board through the bootloader rig on a pty: the rig is a
  # board to a program that is not ours (scripts/avrdude-referee.py says what it checks).
  { [[ -f build/avr/mega.hex && -f build/boot/stk500v2_atmega2560.hex ]] || images; } &&
    cmake -S firmware -B build/host -DCMAKE_BUILD_TYPE=Debug >/dev/null &&
    cmake --build build/host --target bootloader_rig -j"$(nproc)" >/dev/null &&
    python3 scripts/avrdude-referee.py
}

case ${1:-all} in
  images) images ;;
  avrdude) avrdude_referee ;;
  host) host ;;
  all) images && host ;;
  *) echo "usage: $0 [images|host|avrdude]" >&2; exit 2 ;;
esac
