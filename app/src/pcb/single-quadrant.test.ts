import { describe, expect, it } from 'vitest';
import { quarterArcCentre } from './single-quadrant';
import { plotFile } from './tracespace';

const EPSILON = 1.5e-4; // the parser's for 4 decimals: 1.5 of the last digit

describe('single-quadrant quarter arcs', () => {
  it('finds the centre of a quarter circle whose sweep floating point puts a hair over 90°', () => {
    // From the MinnowBoard Turbot's top copper (line 491): J0.0125 from (1.045, 0.9025) to (1.0575, 0.915), counter-clockwise.
    const c = quarterArcCentre([1.045, 0.9025], { x: 1.0575, y: 0.915, j: 0.0125 }, 'ccw', EPSILON);
    expect(c![0]).toBeCloseTo(1.045, 12);
    expect(c![1]).toBeCloseTo(0.915, 12);
  });

  it('leaves to the plotter an arc it draws itself, and a truly impossible one', () => {
    expect(quarterArcCentre([0.205, 0.7442], { x: 0.2044, y: 0.7456, i: 0.002 }, 'ccw', EPSILON)).toBeNull();
    expect(quarterArcCentre([0, 0], { x: 0.01, y: 0, i: 0.002 }, 'ccw', EPSILON)).toBeNull(); // the end lies off every circle
    expect(quarterArcCentre([0, 0], { x: 1, y: 1, a: 1 }, 'ccw', EPSILON)).toBeNull(); // by radius: not this path
  });

  it('draws whole the round cut-out Xpedition writes as four quarters, as gerbv does', () => {
    const quarters = ['X10450Y9025D02*', 'G03X10575Y9150J125D01*', 'X10450Y9275I125*', 'X10325Y9150J125*', 'X10450Y9025I125*'];
    const file = ['%MOIN*%', '%FSLAX24Y24*%', 'G74*', 'G36*', ...quarters, 'G37*', 'M02*'].join('\n');
    const plot = plotFile(file, 'gerber');
    expect(plot.warnings.filter((w) => /impossible/.test(w.message))).toEqual([]);
    const fill = plot.objects.find((o) => o.type === 'fill');
    expect(fill?.type === 'fill' && fill.path.map((s) => s.type)).toEqual(['arc', 'arc', 'arc', 'arc']);
  });

  it('does the same where no quadrant mode is set, which the plotter takes for single quadrant', () => {
    // e2e/fixtures/pcb/veribest/EtchLayer2Bottom.gdo: circles of four quarters, and no G74 or G75.
    const circle = ['X3023Y1969D02*', 'G03X1969Y3023I1054D01*', 'X914Y1969J1054*', 'X1969Y914I1055*', 'X3023Y1969J1055*', 'G01*'];
    const plot = plotFile(['%MOIN*%', '%FSLAX24Y24*%', '%ADD10C,0.0100*%', 'D10*', ...circle, ...circle, 'M02*'].join('\n'), 'gerber');
    expect(plot.warnings.filter((w) => /impossible/.test(w.message))).toEqual([]);
    const arcs = plot.objects.flatMap((o) => (o.type === 'stroke' ? o.path : [])).filter((s) => s.type === 'arc');
    expect(arcs).toHaveLength(8);
    for (const a of arcs) expect(a.type === 'arc' && a.sweep).toBeCloseTo(Math.PI / 2, 5);
  });
});
