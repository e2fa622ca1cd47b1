#!/usr/bin/env bash
# npm run bench: speed and size figures, each printed against a baseline run beside it.
set -euo pipefail
cd "$(dirname "$0")/.."
npm run --silent build >/dev/null  # the editor benchmark runs the built app
# P12 runs the ESP's hub built for the host
cmake -S firmware -B build/host -DCMAKE_BUILD_TYPE=Debug >/dev/null
cmake --build build/host -j"$(nproc)" --target esp_host >/dev/null
npx tsx bench/run.ts
echo
bash scripts/build-avr.sh
echo
echo "Printhead timing, measured on the pins of build/avr/nano.elf in simavr:"
cmake -S firmware -B build/host -DCMAKE_BUILD_TYPE=Debug >/dev/null
cmake --build build/host -j"$(nproc)" --target nano_sim_tests mega_sim_tests >/dev/null
build/host/nano_sim_tests --gtest_brief=1 | grep '^\[nano budget\]'
echo
echo "Motion controller, measured on build/avr/mega.elf driving the Nano image in simavr:"
build/host/mega_sim_tests --gtest_brief=1 | grep '^\[mega budget\]'
