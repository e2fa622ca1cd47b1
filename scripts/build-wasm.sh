#!/usr/bin/env bash
# Builds the machine's firmware cores as WebAssembly (firmware/wasm/printer_module.cpp) with
# Debian's clang, wasi-libc and libc++ for wasm32 (scripts/system-deps.sh installs them): the same
# sources as the AVR images and the host tests, nothing forked for it. The simulated printer runs
# the committed app/src/sim/wasm/printer.wasm, so `npm start` needs no compiler:
#   bash scripts/build-wasm.sh          rebuilds it from the sources (commit it with them);
#   bash scripts/build-wasm.sh --check  fails if the sources no longer build those exact bytes.
set -euo pipefail
cd "$(dirname "$0")/.."
committed=app/src/sim/wasm/printer.wasm

out=build/wasm
mkdir -p "$out/obj"
# One build at a time: the Vitest files that load the module each ask for it, in parallel workers.
exec 9>"$out/.lock"
flock 9
srcs=(firmware/common/protocol/src/*.cpp firmware/common/planner/src/*.cpp firmware/mega/src/*.cpp
  firmware/nano/src/fire_plan.cpp firmware/nano/src/thermal_guard.cpp firmware/nano/src/printhead.cpp
  firmware/nano/src/scan_store.cpp firmware/nano/src/dose_tally.cpp firmware/wasm/printer_module.cpp)
flags=(--target=wasm32-wasi --sysroot=/usr -isystem /usr/include/wasm32-wasi/c++/v1 -isystem /usr/include/wasm32-wasi
  -O2 -std=c++17 -fno-exceptions -Wall -Wextra -Wno-missing-field-initializers
  -Ifirmware/common/protocol/src -Ifirmware/common/planner/src -Ifirmware/mega/src -Ifirmware/nano/src -Ifirmware/virtual)
objs=()
pids=()
for src in "${srcs[@]}"; do
  [[ $src == firmware/mega/src/main.cpp ]] && continue  # the board's own main; printer_module.cpp is the module's
  obj=$out/obj/$(echo "$src" | tr / _).o
  objs+=("$obj")
  # Any header newer than the object rebuilds it: a plain rule, since these few files take seconds.
  if [[ ! -f $obj || $src -nt $obj || -n $(find firmware -name '*.h' -newer "$obj" -print -quit) ]]; then
    rm -f "$obj"
    clang++ "${flags[@]}" -Werror -c "$src" -o "$obj" &
    pids+=($!)
    if ((${#pids[@]} >= $(nproc))); then wait "${pids[0]}"; pids=("${pids[@]:1}"); fi
  fi
done
for pid in "${pids[@]}"; do wait "$pid"; done  # set -e: a failed compile ends the build here
# A reactor: no main, its exports called by the host; the C++ runtime from wasi's libc++ and libc++abi.
clang++ --target=wasm32-wasi --sysroot=/usr -mexec-model=reactor -Wl,--strip-all -Wl,-L/usr/lib/wasm32-wasi \
  -o "$out/printer.wasm" "${objs[@]}" -lc++ -lc++abi
echo "build/wasm/printer.wasm: $(stat -c %s "$out/printer.wasm") B, $(gzip -9c "$out/printer.wasm" | wc -c) B gzipped"
if [[ ${1:-} == --check ]]; then
  if ! cmp -s "$out/printer.wasm" "$committed"; then
    echo "$committed is not what the firmware's sources build: run npm run build:wasm and commit it" >&2
    exit 1
  fi
  echo "$committed: the sources build it byte for byte"
elif ! cmp -s "$out/printer.wasm" "$committed"; then
  cp "$out/printer.wasm" "$committed"
  echo "$committed: updated"
fi
