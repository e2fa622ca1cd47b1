#!/usr/bin/env bash
# The tests of code that two threads run at once, built with clang's ThreadSanitizer in build/tsan
# (firmware/CMakeLists.txt, UV_TSAN): the hand-over between the ESP32's network task and loop()
# (firmware/esp/test/hand_over_race_test.cpp). A reported race fails the run.
set -euo pipefail
cd "$(dirname "$0")/.."

build=build/tsan
CC=clang CXX=clang++ cmake -S firmware -B "$build" -DUV_TSAN=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" -j"$(nproc)" --target esp_race_tests >/dev/null
# A binary built without the sanitizer would pass whatever it does.
grep -q __tsan_init <(nm "$build/esp_race_tests") || { echo "[tsan] esp_race_tests is not built with ThreadSanitizer"; exit 1; }
export TSAN_OPTIONS="halt_on_error=1 exitcode=66 second_deadlock_stack=1"
# Ten runs: the threads meet differently each time (about 0.6 s a run).
"$build/esp_race_tests" --gtest_brief=1 --gtest_repeat=10
