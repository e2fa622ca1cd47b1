#!/usr/bin/env bash
# Builds the real Arduino bootloaders from the sources Debian ships in arduino-core-avr, for the
# simavr rig (firmware/boot/bootloader_rig.cpp) the browser's flasher is tested against:
#   build/boot/optiboot_atmega328.hex     Optiboot, STK500 v1 at 115200 (the Nano since 2018)
#   build/boot/atmegaboot_atmega328.hex   the old Nano bootloader, STK500 v1 at 57600 (Debian's hex as shipped)
#   build/boot/stk500v2_atmega2560.hex    the Mega 2560's wiring/STK500 v2 bootloader at 115200
# Debian's own optiboot_atmega328.hex, rebuilt with its avr-gcc 5.4, is 532 B: it runs past the end of
# flash and its version word overwrites its code. The flags below (the Makefile's, with gcc 4's
# -mshort-calls replaced by section garbage collection and two loop passes off) bring it to 504 B.
set -euo pipefail
cd "$(dirname "$0")/.."

SRC=/usr/share/arduino/hardware/arduino/avr/bootloaders
OUT=build/boot
mkdir -p "$OUT"

optiboot() {
  avr-gcc -g -Wall -Os -fno-inline-small-functions -fno-split-wide-types -mrelax -fno-tree-scev-cprop -fno-ipa-sra \
    -ffunction-sections -fdata-sections -mmcu=atmega328p -DF_CPU=16000000L -DLED_START_FLASHES=3 -DBAUD_RATE=115200 \
    -Wl,--section-start=.text=0x7e00 -Wl,--section-start=.version=0x7ffe -Wl,--relax -Wl,--gc-sections -nostartfiles -nostdlib \
    -o "$OUT/optiboot_atmega328.elf" "$SRC/optiboot/optiboot.c" 2>/dev/null
  local size
  size=$(avr-size -A "$OUT/optiboot_atmega328.elf" | awk '$1 == ".text" { print $2 }')
  if ((size > 510)); then
    echo "FAIL: Optiboot is $size B, over its 512 B boot section less the version word" >&2
    return 1
  fi
  avr-objcopy -O ihex -j .text -j .version "$OUT/optiboot_atmega328.elf" "$OUT/optiboot_atmega328.hex"
}

stk500v2() {
  # Built in a copy: the sources include their headers by relative path.
  local dir=$OUT/stk500v2-src
  mkdir -p "$dir"
  cp "$SRC"/stk500v2/*.c "$SRC"/stk500v2/*.h "$dir"/
  avr-gcc -mmcu=atmega2560 -DF_CPU=16000000UL -D_MEGA_BOARD_ -DBAUDRATE=115200 -Os -funsigned-char -funsigned-bitfields \
    -fpack-struct -fshort-enums -fno-jump-tables -Wl,--section-start=.text=3E000 -nostartfiles \
    -o "$OUT/stk500v2_atmega2560.elf" "$dir/stk500boot.c" 2>/dev/null
  avr-objcopy -O ihex -R .eeprom "$OUT/stk500v2_atmega2560.elf" "$OUT/stk500v2_atmega2560.hex"
}

optiboot
stk500v2
cp "$SRC/atmega/ATmegaBOOT_168_atmega328.hex" "$OUT/atmegaboot_atmega328.hex"
