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

# The check `pio run` makes of the full build's static RAM (firmware/mega/ram_budget.py), tested here
# since PlatformIO cannot run on these machines.
if ! checked=$(python3 firmware/mega/ram_budget_test.py 2>&1); then
  echo "$checked" >&2
  echo "FAIL: firmware/mega/ram_budget.py" >&2
  exit 1
fi
echo "pio run's static-RAM check (firmware/mega/ram_budget.py): $(echo "$checked" | grep '^Ran ')"

echo "AVR images (build/avr):"
# Nano: 32 KB minus the 2 KB old bootloader (the new 512 B Optiboot leaves more); Mega: 256 KB minus 8 KB.
report nano 30720 2048 50
report mega 253952 8192 60

# This Mega image is built without the one library Debian cannot provide: SdFat (the card).
# PlatformIO's build (firmware/mega/platformio.ini) adds it, and `pio run` checks its real figure
# (firmware/mega/ram_budget.py). Here the full build is the Debian image plus what the card was
# measured to add, plus a margin for what that measurement may miss (firmware/mega/card_ram.txt says
# how it was measured). This check holds it to 55 %, though `pio run` fails only over 60 %
# (platformio.ini): the 5 % between them is the room that compiler drift and an estimate's error
# must never use up in a user's build.
card_value() { sed -n "s/^$1=\([0-9]*\)\$/\1/p" firmware/mega/card_ram.txt; }
card=$(card_value CARD_RAM_BYTES); margin=$(card_value ESTIMATE_MARGIN_BYTES)
if [[ -z $card || -z $margin ]]; then
  echo "FAIL: firmware/mega/card_ram.txt gives no CARD_RAM_BYTES or ESTIMATE_MARGIN_BYTES" >&2
  exit 1
fi
mega_static=$(( $(section build/avr/mega.elf .data) + $(section build/avr/mega.elf .bss) ))
with=$((mega_static + card + margin))
pct=$((with * 1000 / 8192))
printf 'mega  full build (with the card, as PlatformIO builds it): static RAM at most %5d / %5d B (%2d.%d %%, budget 55 %%; pio run fails over 60 %%) = this image %d + the card %d + margin %d\n' \
  "$with" 8192 $((pct / 10)) $((pct % 10)) "$mega_static" "$card" "$margin"
if (( with * 100 > 8192 * 55 )); then
  echo "FAIL: mega with SdFat would be over its 55 % static-RAM budget, by $((with - 8192 * 55 / 100)) B" >&2
  exit 1
fi
