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
# PlatformIO's build (firmware/mega/platformio.ini) adds it. What it costs, measured on 2026-11-23 by
# building these sources against SdFat 2.3.1 by hand (avr-size, avr-nm), not guessed from its sources:
# with SdFat, SdStorage is 716 B (SdFat32 612, three FatFile of 32, its own 8; File32 would be 44
# each); SdFat adds 8 B beside it (FatVolume::m_cwv, SPIClass::initialized, .data and padding).
# Without SdFat, SdStorage is a 512-byte buffer that stream mode uses instead of SdFat's sector cache:
# its size is read from this image, so a change to it cannot make the estimate drift. `pio run` checks
# the real figure too (firmware/mega/ram_budget.py).
sdstorage_full=716; sdfat_statics=8
# awk reads to the end: leaving early would end avr-nm with SIGPIPE, which pipefail makes fatal.
sd_hex=$(avr-nm -S build/avr/mega.elf | awk '$4 ~ /_GLOBAL__N_12sdE/ && !found { print $2; found = 1 }')
if [[ -z $sd_hex ]]; then
  echo "FAIL: no SdStorage object (main.cpp's sd) in build/avr/mega.elf to estimate the full build from" >&2
  exit 1
fi
sd_here=$((16#$sd_hex))
mega_static=$(( $(section build/avr/mega.elf .data) + $(section build/avr/mega.elf .bss) ))
with=$((mega_static - sd_here + sdstorage_full + sdfat_statics))
pct=$((with * 1000 / 8192))
printf 'mega  as PlatformIO builds it (SdStorage %d B with SdFat, %d B here; SdFat statics %d B): static RAM about %5d / %5d B (%2d.%d %%, budget 60 %%)\n' \
  "$sdstorage_full" "$sd_here" "$sdfat_statics" "$with" 8192 $((pct / 10)) $((pct % 10))
if (( with * 100 > 8192 * 60 )); then
  echo "FAIL: mega with SdFat would be over its 60 % static-RAM budget" >&2
  exit 1
fi
