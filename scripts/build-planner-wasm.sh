#!/usr/bin/env bash
# Builds the exposure planners as WebAssembly for the app's work worker (firmware/wasm/planner_module.cpp)
# with Debian's clang, wasi-libc and lld for wasm32 (scripts/system-deps.sh installs them), from the same
# sources as the Mega's planner and the host tests, nothing forked. Made for size: -Oz, link-time
# optimisation, unused sections dropped, no names, and bulk memory (memory.copy and memory.fill, in every
# browser with Web Serial) in place of the C library's memcpy and memset. No wasm-opt: system-deps.sh
# installs no binaryen. The committed module is app/src/planner/wasm/planner.wasm:
#   bash scripts/build-planner-wasm.sh          rebuilds it from the sources (commit it with them);
#   bash scripts/build-planner-wasm.sh --check  fails if the sources no longer build those exact bytes.
set -euo pipefail
cd "$(dirname "$0")/.."
committed=app/src/planner/wasm/planner.wasm

out=build/planner-wasm
rm -rf "$out/obj"
mkdir -p "$out/obj"
# The planners and what the scan planner's link check reads of the protocol (the Nano's program lines).
srcs=(firmware/common/planner/src/planner.cpp firmware/common/planner/src/time_model.cpp
  firmware/common/planner/src/scan.cpp firmware/common/planner/src/scan_band.cpp firmware/common/planner/src/glide.cpp
  firmware/common/planner/src/scan_pass.cpp firmware/common/planner/src/scan_stops.cpp
  firmware/common/protocol/src/scan_program.cpp firmware/common/protocol/src/nano_codec.cpp
  firmware/common/protocol/src/crc16.cpp firmware/common/protocol/src/text_scan.cpp
  firmware/common/protocol/src/line_splitter.cpp firmware/wasm/planner_module.cpp)
flags=(--target=wasm32-wasi --sysroot=/usr -isystem /usr/include/wasm32-wasi
  -Oz -flto -fwhole-program-vtables -mbulk-memory -ffunction-sections -fdata-sections -fvisibility=hidden -std=c++17 -fno-exceptions -fno-rtti
  -Wall -Wextra -Wno-missing-field-initializers -Werror
  -Ifirmware/common/protocol/src -Ifirmware/common/planner/src)
objs=()
for src in "${srcs[@]}"; do  # one compile at a time: the machine is shared
  obj=$out/obj/$(echo "$src" | tr / _).o
  clang++ "${flags[@]}" -c "$src" -o "$obj"
  objs+=("$obj")
done
# A reactor: no main, only the exports the module names; no C++ runtime (no exceptions, no RTTI, no heap).
clang++ --target=wasm32-wasi --sysroot=/usr -mexec-model=reactor -nostdlib++ -flto -Oz \
  -Wl,--gc-sections -Wl,--strip-all -Wl,-L/usr/lib/wasm32-wasi \
  -o "$out/planner.wasm" "${objs[@]}"
raw=$(stat -c %s "$out/planner.wasm")
gz=$(gzip -9c "$out/planner.wasm" | wc -c)
echo "$out/planner.wasm: $raw B, $gz B gzipped, $(((gz + 4095) / 4096)) blocks of 4 KB on the ESP"
if [[ ${1:-} == --check ]]; then
  if ! cmp -s "$out/planner.wasm" "$committed"; then
    echo "$committed is not what the planner's sources build: run bash scripts/build-planner-wasm.sh and commit it" >&2
    exit 1
  fi
  echo "$committed: the sources build it byte for byte"
elif ! cmp -s "$out/planner.wasm" "$committed"; then
  mkdir -p "$(dirname "$committed")"
  cp "$out/planner.wasm" "$committed"
  echo "$committed: updated"
fi
