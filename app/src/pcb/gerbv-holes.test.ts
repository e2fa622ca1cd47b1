// Our holes against gerbv's, hole by hole, for every Excellon drill file among Debian's gerbv examples.
// A raster at 50 µm can hide a hole too many or a board read at the wrong scale (most cells are bare
// either way), so each hole's centre and diameter is compared with the one gerbv reads.
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { gerbvExample, gerbvExampleFiles, gerbvHoles, hasGerbv, matchHoles, readGerbvDrill } from './gerbv-reference';
import type { Hole } from './plot-to-artwork';
import { readBoard, type BoardLayer } from './read-board';
import { fileType } from './tracespace';

/** gerbv writes four decimals of an inch (2.5 µm): a hole read alike lies within this. */
const TOLERANCE_MM = 0.005;
/** Its tool sizes to three decimals of an inch: 12.7 µm. */
const DIAMETER_TOLERANCE_MM = 0.0128;
const MISSING = 'gerbv and its examples are missing: `bash scripts/system-deps.sh` installs them (Debian package gerbv)';

/**
 * Files where gerbv is the one that misreads, and how ours is shown right instead. Anything else must
 * agree with gerbv hole for hole.
 */
const GERBV_MISREADS: Record<string, string> = {
  // ";FILE_FORMAT=2:3", "INCH,LZ": leading zeros kept, trailing ones left out, so X0152 is 01.52 in and
  // X03035 is 03.035 in. gerbv reads the shorter numbers with one digit before the point (0.152 in).
  'protel-pnp/SE_SG_IF_V2.TXT': 'protel-pnp/SE_SG_IF_V2.GTL',
  // Routed slots only (G00 to the start, M15 plunge, G01 along, M16 lift): no drill hits at all. gerbv
  // counts the route's points as hits, 805 mm up.
  'amacro-ref/jj1.drl': '',
};

/**
 * Tools gerbv cannot read, so its holes take another tool's size: "T0C0.006" in ekf2's header ("Undefined
 * code 'C'"). Our diameter for them, mm.
 */
const GERBV_MISSES_TOOL: Record<string, number[]> = { 'ekf2/drill20.exc': [0.1524], 'ekf2/drill30.exc': [0.1524] };

const results: string[] = [];
const dir = mkdtempSync(join(tmpdir(), 'gerbv-holes-'));

function readOne(file: string): { layer: BoardLayer | undefined; path: string; problems: string[] } {
  const source = gerbvExample(file, dir)!;
  const set = readBoard([{ name: file.split('/').pop()!, text: source.text }]);
  return { layer: set.layers[0], path: source.path, problems: set.problems.map((p) => p.message) };
}

/** Whether a hole's centre lies on a pad (a flash, not a track or a pour) of the copper layer. */
function onPad(copper: BoardLayer, h: Hole): boolean {
  return copper.paints.some((p) => !p.clear && p.shape.kind !== 'stadium' && p.shape.kind !== 'polygon' && p.box.x0 <= h.x && h.x <= p.box.x1 && p.box.y0 <= h.y && h.y <= p.box.y1);
}

const drillFiles = gerbvExampleFiles().filter((file) => {
  const source = gerbvExample(file, dir);
  return source !== null && !/[\0-\x08\x0e-\x1f]/.test(source.text.slice(0, 4096)) && fileType(source.text) === 'drill';
});

describe('holes agree with gerbv’s, every drill file of its examples', () => {
  afterAll(() => {
    rmSync(dir, { recursive: true, force: true });
    console.log(`\nHoles read alike with gerbv (within ${TOLERANCE_MM * 1000} µm):\n${results.join('\n')}`);
  });

  it('has gerbv and its drill examples to compare with', () => {
    expect(hasGerbv(), MISSING).toBe(true);
    // hellboard (gEDA), nollezappare (Veribest), orcad, ekf2, protel-pnp, amacro-ref (Mentor), numpres (gEDA, old)
    expect(drillFiles.length, MISSING).toBeGreaterThanOrEqual(11);
  });

  it.each(drillFiles.filter((f) => !(f in GERBV_MISREADS)))('%s', (file) => {
    const { layer, path, problems } = readOne(file);
    const ours = layer?.holes ?? [];
    const theirs = gerbvHoles(path);
    const m = matchHoles(ours, theirs, TOLERANCE_MM, DIAMETER_TOLERANCE_MM);
    results.push(`  ${file.padEnd(46)} gerbv ${String(theirs.length).padStart(5)}  ours ${String(ours.length).padStart(5)}  alike ${String(m.matched).padStart(5)}  furthest ${(m.worstMm * 1000).toFixed(1)} µm`);
    expect(problems.filter((p) => p !== 'the drill file has no holes'), file).toEqual([]);
    expect(ours.length, `${file}: holes`).toBe(theirs.length);
    expect(m.matched, `${file}: holes within ${TOLERANCE_MM} mm of gerbv's`).toBe(theirs.length);
    expect(m.diametersDiffering, `${file}: diameters`).toEqual(GERBV_MISSES_TOOL[file] ?? []);
  }, 120_000);

  it('Veribest’s .ncd: its zero set (G93X000000Y000000) drills nothing, so the board is 91.5 × 71.2 mm as gerbv reads it', () => {
    const { layer } = readOne('nollezappare/ThruHolePlated.ncd');
    const b = layer!.boundsMm;
    expect(layer!.holes.some((h) => Math.hypot(h.x, h.y) < 1)).toBe(false);
    expect(b.x1 - b.x0).toBeCloseTo(91.459, 2);
    expect(b.y1 - b.y0).toBeCloseTo(71.18, 2);
  });

  it('Protel’s trailing-suppressed drill file: every hole of ours lies on a pad of the top copper, gerbv’s do not', () => {
    const file = 'protel-pnp/SE_SG_IF_V2.TXT';
    const { layer, path } = readOne(file);
    const copper = readOne(GERBV_MISREADS[file]).layer!;
    const theirs = gerbvHoles(path);
    const ours = layer!.holes;
    expect(ours).toHaveLength(427);
    expect(ours.filter((h) => onPad(copper, h))).toHaveLength(ours.length);
    const theirsOnPads = theirs.filter((h) => onPad(copper, h)).length;
    expect(theirsOnPads).toBeLessThan(theirs.length);
    results.push(`  ${file.padEnd(46)} gerbv ${String(theirs.length).padStart(5)}  ours ${String(ours.length).padStart(5)}  on the copper's pads: ours ${ours.length}, gerbv's ${theirsOnPads} (gerbv misreads)`);
  }, 120_000);

  it('Mentor’s routed slots (jj1.drl): no drill hits, the routes drawn', () => {
    const { layer } = readOne('amacro-ref/jj1.drl');
    expect(layer!.holes).toEqual([]);
    expect(layer!.paints.length).toBeGreaterThan(0);
    expect(layer!.paints.every((p) => p.shape.kind === 'stadium')).toBe(true);
    results.push(`  ${'amacro-ref/jj1.drl'.padEnd(46)} routed slots only: ours 0 holes, ${layer!.paints.length} route strokes (gerbv reads route points as holes)`);
  });
});

describe('gerbv’s drill export read back', () => {
  it('reads tools and four-decimal inch coordinates in millimetres', () => {
    const holes = readGerbvDrill('M48\nINCH,TZ\nT10C0.034\nT11C0.043\n%\nT10\nX015945Y002469\nT11\nX000000Y010000\nM30\n');
    expect(holes.map((h) => [+h.x.toFixed(4), +h.y.toFixed(4), +h.diameterMm.toFixed(4)])).toEqual([
      [40.5003, 6.2713, 0.8636],
      [0, 25.4, 1.0922],
    ]);
  });

  it('refuses a format it does not know rather than read it wrong', () => {
    expect(() => readGerbvDrill('M48\nMETRIC,LZ\n%\n')).toThrow(/format/);
  });

  it('pairs each of gerbv’s holes with one of ours at most once', () => {
    const h = (x: number, y: number) => ({ x, y, diameterMm: 1 });
    expect(matchHoles([h(0, 0)], [h(0, 0), h(0, 0)], 0.01, 0.01)).toMatchObject({ matched: 1 });
    expect(matchHoles([h(0, 0), h(5, 0.004)], [h(5, 0), h(0, 0)], 0.005, 0.01)).toEqual({ matched: 2, worstMm: 0.004, diametersDiffering: [] });
  });
});
