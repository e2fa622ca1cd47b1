// Puts the firmware images beside the app (dist/app/firmware/) with the manifest the Firmware view reads
// (app/src/firmware/manifest.ts): each image's board, version, how it was built, and each file's SHA-256.
//
//   node scripts/firmware-manifest.mjs             this machine's images (build/avr: the Nano's, and the
//                                                   Mega's without its SD card), when they are built
//   npx tsx scripts/firmware-manifest.mjs --pio DIR   the images PlatformIO built, collected in DIR/<env>/ by
//                                                   the public workflow (.github/workflows/firmware.yml); the
//                                                   ESP32's offsets are read from the partitions.bin it built
import { createHash } from 'node:crypto';
import { copyFileSync, existsSync, mkdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';

const root = new URL('..', import.meta.url).pathname;
const out = join(root, 'dist', 'app', 'firmware');

const versionOf = {
  nano: () => /NANO_FIRMWARE_VERSION "([^"]+)"/.exec(readFileSync(join(root, 'firmware/nano/src/config.h'), 'utf8'))[1],
  mega: () => /kFirmwareName\[\] UV_FLASH = "UVExposure ([^ "]+)/.exec(readFileSync(join(root, 'firmware/mega/src/main.cpp'), 'utf8'))[1],
};

function part(from, file, offset) {
  copyFileSync(from, join(out, file));
  const bytes = readFileSync(from);
  return { file, offset, sha256: createHash('sha256').update(bytes).digest('hex'), bytes: bytes.length };
}

const images = [];
rmSync(out, { recursive: true, force: true });
mkdirSync(out, { recursive: true });
const pio = process.argv.indexOf('--pio');
if (pio > 0) {
  // The workflow's artifacts: <env>/firmware.hex (AVR); <env>/*.bin (ESP).
  const dir = process.argv[pio + 1];
  const espVersion = versionOf.mega(); // the hub is released with the Mega
  const avr = [['nanoatmega328new', 'nano'], ['megaatmega2560', 'mega']];
  for (const [env, board] of avr) {
    const hex = join(dir, env, 'firmware.hex');
    if (existsSync(hex)) images.push({ board, version: versionOf[board](), built: 'PlatformIO', parts: [part(hex, `${board}.hex`, 0)] });
  }
  // Where each file goes: the ESP8266's by its linker script (app/src/firmware/esp-layout.json, which the
  // Firmware view checks a person's own files by), the ESP32's by the partition table its build wrote.
  const layout = JSON.parse(readFileSync(join(root, 'app/src/firmware/esp-layout.json'), 'utf8'));
  const { esp32Layout } = await import('../app/src/firmware/esp-layout.ts'); // run under tsx
  const regions = (env, board) => {
    const table = join(dir, env, 'partitions.bin');
    return board === 'esp32' && existsSync(table) ? esp32Layout(new Uint8Array(readFileSync(table))) : layout[board];
  };
  const esp = [['esp12e', 'esp8266'], ['esp32dev', 'esp32']].map(([env, board]) => [env, board, regions(env, board).map((r) => [r.file, r.offset])]);
  for (const [env, board, files] of esp) {
    if (!files.every(([f]) => existsSync(join(dir, env, f)))) continue;
    images.push({ board, version: espVersion, built: 'PlatformIO', parts: files.map(([f, offset]) => part(join(dir, env, f), `${board}-${f}`, offset)) });
  }
} else {
  const nano = join(root, 'build/avr/nano.hex');
  const mega = join(root, 'build/avr/mega.hex');
  if (existsSync(nano)) images.push({ board: 'nano', version: versionOf.nano(), built: 'Debian avr-gcc, this machine', parts: [part(nano, 'nano.hex', 0)] });
  if (existsSync(mega)) {
    images.push({
      board: 'mega', version: versionOf.mega(), built: 'Debian avr-gcc, this machine', parts: [part(mega, 'mega.hex', 0)],
      lacks: 'has no SD card support (SdFat is not in Debian): jobs stream over USB or Wi-Fi, none are kept on a card. The published image, built by PlatformIO, has it.',
    });
  }
}
writeFileSync(join(out, 'manifest.json'), JSON.stringify({ images }, null, 2) + '\n');
console.log(`[firmware] ${images.length} image(s) in ${out}: ${images.map((i) => `${i.board} ${i.version} (${i.parts.map((p) => `${p.bytes} B`).join(' + ')})`).join(', ') || 'none (build them: npm run test:firmware images)'}`);
