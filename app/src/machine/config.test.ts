import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { expect, it } from 'vitest';
import { SimHost } from '../sim/sim-host.fixture';
import { BOARD_LINK_BAUD, CONFIG_DEFAULTS, linkBaudOf, MAX_STEP_RATE, motionOf, topSpeedUmS } from './config';

const ROOT = fileURLToPath(new URL('../../..', import.meta.url));

it('settings-table.ts, the C++ keys and CONFIG.md are what firmware/mega/settings.toml generates', () => {
  // scripts/settings.py --check names each generated file that differs, and fails.
  expect(() => execFileSync('python3', ['scripts/settings.py', '--check'], { cwd: ROOT, encoding: 'utf8', stdio: 'pipe' })).not.toThrow();
});

it('loads CONFIG.TXT as CONFIG.md says: good lines taken, every other line skipped', () => {
  const h = new SimHost();
  h.sim.module.putFile('CONFIG.TXT', ['# a comment', '', 'accel.x=2500', '  speed.z = 2.5  ', 'accel.y = fast', 'nozzle = 3', 'led.offset.1 = 1,4', 'bed.x 300'].join('\n'));
  h.cmd('M501');
  const value = (key: string) => h.cmd(`M850 ${key}`)[0];
  expect(value('accel.x')).toBe('M850 accel.x 2500');
  expect(value('speed.z')).toBe('M850 speed.z 2.5');
  expect(value('accel.y')).toBe('M850 accel.y 1500');
  expect(value('led.offset.1')).toBe('M850 led.offset.1 1,4');
  expect(value('bed.x')).toBe('M850 bed.x 200');
  h.cmd('M500');
  expect(new Map(h.sim.module.card()).get('CONFIG.TXT')!.split('\n')[0]).toBe('steps_per_mm.x = 80');
});

it('keeps an EEPROM copy for a printer without a card, through a power cycle', () => {
  const h = new SimHost({ noSd: true });
  h.cmd('M850 bed.x 300');
  expect(h.cmd('M500')[0]).toBe('echo:Settings stored in EEPROM only: no SD card');
  h.sim.powerCycle(); // right after: M500 answered once the EEPROM held them
  h.reconnect();
  expect(h.cmd('M850 bed.x')[0]).toBe('M850 bed.x 300');
  h.cmd('M502');
  expect(h.cmd('M850 bed.x')[0]).toBe('M850 bed.x 200');
  h.cmd('M501');
  expect(h.cmd('M850 bed.x')[0]).toBe('M850 bed.x 300');
});

it('plans no axis faster than the Mega steps it: the setting, or 16000 steps/s at its steps/mm', () => {
  expect(motionOf(CONFIG_DEFAULTS).vmaxUmS).toEqual([100_000, 100_000]); // 80 steps/mm: 8000 steps/s
  // A leadscrew at 1/16 microstepping on X: 100 mm/s would be 40000 steps/s; the Mega runs 40 mm/s.
  const screw = { ...CONFIG_DEFAULTS, 'steps_per_mm.x': '400' };
  expect(motionOf(screw).vmaxUmS).toEqual([40_000, 100_000]);
  expect(topSpeedUmS(screw, 0)).toBe((MAX_STEP_RATE * 1_000_000) / 400_000);
  expect(topSpeedUmS({ ...CONFIG_DEFAULTS, 'steps_per_mm.z': '2000' }, 2)).toBe(8_000); // speed.z 10 mm/s, capped at 8
});

it('plans at the printhead link speed the Mega plans a job at when its Nano takes the raise (printhead_link.h kJobLinkBaud)', () => {
  const h = readFileSync(new URL('../../../firmware/mega/src/printhead_link.h', import.meta.url), 'utf8');
  const raise = /constexpr bool kRaiseNanoLink = (true|false);/.exec(h)?.[1];
  const fast = Number(/constexpr uint32_t kNanoFastBaud = (\d+);/.exec(h)?.[1]);
  expect(raise).toBeDefined();
  expect(h).toContain('kJobLinkBaud = kRaiseNanoLink ? kNanoFastBaud : uv::kNanoBaud;');
  expect(motionOf({}).linkBaud).toBe(raise === 'true' ? fast : 115200);
  expect(motionOf({}, [0, 0], 115200).linkBaud).toBe(115200);
});

it('prices at the link speed the printer reports (Cap:LINK_BAUD), else at BOARD_LINK_BAUD', () => {
  expect(linkBaudOf(115200)).toBe(115200); // a Nano that never takes L: the Mega plans at 115200
  expect(linkBaudOf(250000)).toBe(250000);
  expect(linkBaudOf(null)).toBe(BOARD_LINK_BAUD); // firmware from before Cap:LINK_BAUD
  expect(linkBaudOf(undefined)).toBe(BOARD_LINK_BAUD);
  for (const bad of [0, 9600, 115201, 2 ** 32]) expect(linkBaudOf(bad)).toBe(BOARD_LINK_BAUD); // not a speed the link takes
});
