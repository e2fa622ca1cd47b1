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

# This Mega image is built without the one library Debian cannot provide: SdFat (the card).
# PlatformIO's build (firmware/mega/platformio.ini) adds it. Its static RAM, from its sources:
# SdFat32 is its 512-byte sector cache plus about 60 bytes of volume state and SPI settings; each of
# the three open File32 is 36 bytes. The panel's driver (src/hw/oled) is in this image already.
# Without SdFat, SdStorage keeps its own 512-byte buffer for stream mode; with SdFat, stream mode
# borrows the sector cache instead, so that buffer is not in the full build.
sdfat=$((512 + 60 + 3 * 36)); standin=512
mega_static=$(( $(section build/avr/mega.elf .data) + $(section build/avr/mega.elf .bss) ))
with=$((mega_static - standin + sdfat))
printf 'mega  as PlatformIO builds it (SdFat %d B, less the %d B stand-in cache): static RAM about %5d / %5d B (%2d %%, budget 60 %%)\n' \
  "$sdfat" "$standin" "$with" 8192 $((with * 100 / 8192))
if (( with * 100 > 8192 * 60 )); then
  echo "FAIL: mega with its libraries would be over its 60 % static-RAM budget" >&2
  exit 1
fi
