#!/usr/bin/env bash
# Builds build/avr/nano.elf and build/avr/mega.elf with Debian's AVR toolchain and checks
# their flash and static-RAM budgets (static RAM = .data + .bss, what avr-size calls Data).
set -euo pipefail
cd "$(dirname "$0")/.."

jobs=$(nproc 2>/dev/null || echo 2)
make -s -f firmware/avr.mk BOARD=nano -j"$jobs"
make -s -f firmware/avr.mk BOARD=mega -j"$jobs"

section() { avr-size -A "$1" | awk -v s="$2" '$1 == s { print $2 }'; }

# board  flash available (bytes, after the bootloader)  RAM  RAM budget %
report() {
  local board=$1 flash_max=$2 ram=$3 budget=$4
  local elf=build/avr/$board.elf
  local text data bss flash static pct
  text=$(section "$elf" .text); data=$(section "$elf" .data); bss=$(section "$elf" .bss)
  flash=$((text + data)); static=$((data + bss))
  pct=$((static * 1000 / ram))
  printf '%-5s flash %6d / %6d B (%2d.%d %%)   static RAM %5d / %5d B (%2d.%d %%, budget %d %%)\n' \
    "$board" "$flash" "$flash_max" $((flash * 100 / flash_max)) $((flash * 1000 / flash_max % 10)) \
    "$static" "$ram" $((pct / 10)) $((pct % 10)) "$budget"
  if (( static * 100 > ram * budget )); then
    echo "FAIL: $board static RAM over its $budget % budget" >&2
    return 1
  fi
  if (( flash > flash_max )); then
    echo "FAIL: $board does not fit its flash" >&2
    return 1
  fi
}

echo "AVR images (build/avr):"
# Nano: 32 KB minus the 2 KB old bootloader (the new 512 B Optiboot leaves more); Mega: 256 KB minus 8 KB.
report nano 30720 2048 50
report mega 253952 8192 60
