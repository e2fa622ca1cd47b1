import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { readBoard } from './read-board';
import { at, gerber } from './test-boards';

const one = (text: string, name = 'board-F_Cu.gbr') => readBoard([{ name, text }]);
const holesOf = (text: string) => one(text, 'board.drl').layers[0]?.holes.map((h) => ({ x: +h.x.toFixed(6), y: +h.y.toFixed(6), d: +h.diameterMm.toFixed(6) }));

describe('a board of several files', () => {
  it('reads each file as a layer of the kind its name suggests, in millimetres, with its bounds', () => {
    const copper = gerber(`%ADD10C,0.5*%\nD10*\n${at(1, 1)}D03*`);
    const outline = gerber(`%ADD10C,0.1*%\nD10*\n${at(0, 0)}D02*\n${at(10, 0)}D01*\n${at(10, 8)}D01*\n${at(0, 8)}D01*\n${at(0, 0)}D01*`);
    const drill = 'M48\nMETRIC\nT1C0.8\n%\nT1\nX1.0Y1.0\nM30\n';
    const set = readBoard([
      { name: 'board-F_Cu.gbr', text: copper },
      { name: 'board-Edge_Cuts.gbr', text: outline },
      { name: 'board-PTH.drl', text: drill },
      { name: 'board-B_Cu.gbr', text: '' },
    ]);
    expect(set.layers.map((l) => [l.file, l.kind, l.format, l.units])).toEqual([
      ['board-F_Cu.gbr', 'copper-top', 'gerber', 'mm'],
      ['board-Edge_Cuts.gbr', 'outline', 'gerber', 'mm'],
      ['board-PTH.drl', 'drill', 'excellon', 'mm'],
    ]);
    expect(set.layers[0].boundsMm).toEqual({ x0: 0.75, y0: 0.75, x1: 1.25, y1: 1.25 });
    expect(set.layers[1].boundsMm).toEqual({ x0: -0.05, y0: -0.05, x1: 10.05, y1: 8.05 });
    expect(set.layers[2].holes).toEqual([{ x: 1, y: 1, diameterMm: 0.8 }]);
    expect(set.problems).toEqual([{ file: 'board-B_Cu.gbr', message: 'the file is empty' }]);
  });

  it('calls an Excellon file a drill layer whatever its name, and keeps a Gerber file whose first line has no *', () => {
    expect(one('M48\nINCH\nT1C0.03\n%\nT1\nX1.0Y1.0\nM30\n', 'holes.txt.gbr').layers[0].kind).toBe('drill');
    // As gEDA PCB writes them: the first comment has no '*' (and swallows the next, a comment too).
    const set = one(`G04 start of page 2 for group 0 idx 0\nG04 Title: (unknown), component *\n%FSLAX46Y46*%\n%MOMM*%\n%ADD10C,1*%\nD10*\n${at(0, 0)}D03*\nM02*\n`);
    expect(set.layers[0].format).toBe('gerber');
  });

  it('splits old blocks that put a mode code before a draw, so the draw is kept', () => {
    const set = one(`%FSLAX23Y23*%\n%MOIN*%\n%ADD10C,0.010*%\nG54D10*X1000Y1000D02*G75G03I150J0X1000Y1001D01*G01*\nM02*\n`);
    expect(set.problems).toEqual([]);
    expect(set.layers[0].boundsMm.x1 - set.layers[0].boundsMm.x0).toBeCloseTo((0.3 + 0.01) * 25.4, 3); // a whole circle
  });
});

describe('a board whose files say nothing of copper', () => {
  // 12 pads and tracks in two widths between them: copper's mix. A mask: the same pads, nothing drawn.
  const pads = Array.from({ length: 12 }, (_, i) => `${at(i * 2, 0)}D03*`).join('\n');
  const tracks = Array.from({ length: 6 }, (_, i) => `${at(i * 2, 0)}D02*\n${at(i * 2 + 2, 0)}D01*`).join('\n');
  const copper = gerber(`%ADD10C,1*%\n%ADD11C,0.2*%\n%ADD12C,0.3*%\nD10*\n${pads}\nD11*\n${tracks}\nD12*\n${at(0, 0)}D02*\n${at(0, 5)}D01*`);
  const mask = gerber(`%ADD10C,1.2*%\nD10*\n${pads}`);

  it('takes the first that draws as copper does for the top copper, saying it was from what it draws', () => {
    const set = readBoard([{ name: 'artwork_2.grb', text: mask }, { name: 'artwork_1.grb', text: copper }]);
    expect(set.layers.map((l) => [l.file, l.kind, l.kindFrom])).toEqual([
      ['artwork_2.grb', 'other', 'none'],
      ['artwork_1.grb', 'copper-top', 'content'],
    ]);
  });

  it('leaves them alone when another file says it is copper, or none draws as copper does', () => {
    expect(readBoard([{ name: 'a.GBL', text: mask }, { name: 'artwork_1.grb', text: copper }]).layers.map((l) => l.kind)).toEqual(['copper-bottom', 'other']);
    expect(readBoard([{ name: 'artwork_2.grb', text: mask }]).layers.map((l) => l.kind)).toEqual(['other']);
  });

  it('never takes a file named as something else, a drawing or a legend, for copper', () => {
    expect(readBoard([{ name: 'AssemblyTop.gdo', text: copper }, { name: 'sieb0.grb', text: copper }]).layers.map((l) => l.kind)).toEqual(['other', 'other']);
  });
});

describe('a file as KiCad 7 writes it', () => {
  // X2 attributes, KiCad's RoundRect macro, a trace and a region, in KiCad's negative Y.
  const KICAD = `%TF.GenerationSoftware,KiCad,Pcbnew,7.0.10*%
%TF.CreationDate,2024-01-01T00:00:00+00:00*%
%TF.ProjectId,demo,64656d6f,rev?*%
%TF.SameCoordinates,Original*%
%TF.FileFunction,Copper,L1,Top*%
%TF.FilePolarity,Positive*%
%FSLAX46Y46*%
G04 Gerber Fmt 4.6, Leading zero omitted, Abs format (unit mm)*
G04 Created by KiCad (PCBNEW 7.0.10) date 2024-01-01 00:00:00*
%MOMM*%
%LPD*%
G01*
G04 APERTURE LIST*
%TA.AperFunction,ComponentPad*%
%ADD10R,1.700000X1.700000*%
%TD*%
%TA.AperFunction,ComponentPad*%
%ADD11O,1.700000X1.700000*%
%TD*%
%TA.AperFunction,Conductor*%
%ADD12C,0.250000*%
%TD*%
%AMRoundRect*
0 Rectangle with rounded corners*
0 $1 Rounding radius*
0 $2 $3 $4 $5 $6 $7 $8 $9 X,Y pos of 4 corners*
0 Add a 4 corners polygon primitive as box body*
4,1,4,$2,$3,$4,$5,$6,$7,$8,$9,$2,$3,0*
0 Add four circle primitives for the rounded corners*
1,1,$1+$1,$2,$3*
1,1,$1+$1,$4,$5*
1,1,$1+$1,$6,$7*
1,1,$1+$1,$8,$9*
0 Add four rect primitives between the rounded corners*
20,1,$1+$1,$2,$3,$4,$5,0*
20,1,$1+$1,$4,$5,$6,$7,0*
20,1,$1+$1,$6,$7,$8,$9,0*
20,1,$1+$1,$8,$9,$2,$3,0*%
%TA.AperFunction,SMDPad,CuDef*%
%ADD13RoundRect,0.250000X-0.450000X0.350000X0.450000X0.350000X0.450000X-0.350000X-0.450000X-0.350000X0*%
%TD*%
G04 APERTURE END LIST*
D10*
%TO.P,J1,1,Pin_1*%
%TO.N,Net-(J1-Pin_1)*%
X100000000Y-100000000D03*
%TD*%
D11*
X102540000Y-100000000D03*
D13*
X105000000Y-100000000D03*
D12*
%TO.N,Net-(J1-Pin_1)*%
X100000000Y-100000000D02*
X100000000Y-95000000D01*
X105000000Y-95000000D01*
%TD*%
%TA.AperFunction,Conductor*%
%TD*%
G36*
X110000000Y-90000000D02*
G01*
X115000000Y-90000000D01*
X115000000Y-85000000D01*
X110000000Y-85000000D01*
X110000000Y-90000000D01*
G37*
M02*
`;

  it('reads without problems or notes, rounded pads and all', () => {
    const set = one(KICAD);
    expect(set.problems).toEqual([]);
    expect(set.layers[0].notes).toEqual([]);
    expect(set.layers[0].boundsMm).toEqual({ x0: 99.15, y0: -100.85, x1: 115, y1: -85 });
    const roundRect = set.layers[0].paints[2].box;
    expect([roundRect.x1 - roundRect.x0, roundRect.y1 - roundRect.y0].map((v) => +v.toFixed(9))).toEqual([1.4, 1.2]);
  });
});

describe('what cannot be used is a problem, never a throw or a silent empty layer', () => {
  it.each([
    ['an empty file', '  \n', 'the file is empty'],
    ['prose', 'Hello,\nthis is a README.\n', 'not a Gerber or Excellon drill file'],
    ['a binary file', '\x00\x01\x02PK\x03\x04 zip', 'not a Gerber or Excellon drill file: it is not text'],
    ['a Gerber file of comments only', gerber('G04 nothing here*'), 'the Gerber file draws nothing'],
    ['a macro primitive the library does not know', gerber(`%AMODD*\n99,1,2*%\n%ADD10ODD,1*%\nD10*\n${at(0, 0)}D03*`), 'could not be read: '],
  ])('%s', (_, text, message) => {
    const set = one(text);
    expect(set.layers).toEqual([]);
    expect(set.problems).toHaveLength(1);
    expect(set.problems[0].message).toContain(message);
  });

  it('a layer that draws nothing, as is normal for its kind, is a quiet note; copper or an outline that draws nothing is a problem', () => {
    const emptyPaste = gerber('%TF.FileFunction,Paste,Bot*%\nG04 APERTURE LIST*\nG04 APERTURE END LIST*');
    for (const [name, text] of [
      ['board-B_Paste.gbr', emptyPaste],
      ['board-B_Silkscreen.gbr', gerber('G04 nothing here*')],
      ['board-NPTH.drl', 'M48\nMETRIC\nT1C0.8\n%\nM30\n'],
      ['board.gbr', emptyPaste], // the attribute says paste, whatever the name
    ]) {
      const set = one(text, name);
      expect([set.layers, set.problems], name).toEqual([[], []]);
      expect(set.notes.map((n) => n.message), name).toEqual([name.endsWith('.drl') ? 'the drill file has no holes' : 'the Gerber file draws nothing']);
    }
    for (const name of ['board-F_Cu.gbr', 'board-Edge_Cuts.gbr', 'board.gbr']) {
      const set = one(gerber('G04 nothing here*'), name);
      expect([set.problems.map((p) => p.message), set.notes], name).toEqual([['the Gerber file draws nothing'], []]);
    }
    // Something there that could not be drawn is a problem whatever the kind.
    const lost = one(gerber('%ADD11NOSUCHMACRO*%\nD11*\nX0Y0D03*'), 'board-B_Paste.gbr');
    expect(lost.notes).toEqual([]);
    expect(lost.problems.map((p) => p.message)).toContain('the Gerber file draws nothing');
  });

  it('keeps a layer but says what was left out or not applied', () => {
    const undefinedTool = one(gerber(`%ADD10C,1*%\nD10*\n${at(0, 0)}D03*\nD11*\n${at(5, 5)}D03*`));
    expect(undefinedTool.layers).toHaveLength(1);
    expect(undefinedTool.problems.map((p) => p.message)).toEqual(['line 7: tool 11 is not defined']);
    const noMacro = one(gerber(`%ADD10C,1*%\n%ADD11NOSUCHMACRO*%\nD10*\n${at(0, 0)}D03*\nD11*\n${at(5, 5)}D03*`));
    expect(noMacro.problems.map((p) => p.message)).toEqual(['aperture 11 has no shape (its macro is not defined or draws nothing): its flashes are left out']);
    const negative = one(gerber(`%IPNEG*%\n%ADD10C,1*%\nD10*\n${at(0, 0)}D03*`));
    expect(negative.layers).toHaveLength(1);
    expect(negative.problems.map((p) => p.message)).toEqual(['a negative image (%IPNEG) is not supported: the layer is drawn positive']);
    expect(one(gerber(`%OFA0B0*%\n%SFA1B1*%\n%MIA0B0*%\n%ADD10C,1*%\nD10*\n${at(0, 0)}D03*`)).problems).toEqual([]);
    expect(one(gerber(`%OFA1.0B0*%\n%ADD10C,1*%\nD10*\n${at(0, 0)}D03*`)).problems.map((p) => p.message)).toEqual(['image offset (%OF) is not applied']);
  });

  it('draws a zero-width aperture’s draws 0.1 mm wide, bounded by their centre line, and says so but of an outline', () => {
    const text = gerber(`%ADD10C,0*%\n%ADD11C,1*%\nD10*\n${at(0, 0)}D02*\n${at(5, 0)}D01*\nD11*\n${at(0, 0)}D03*`);
    const set = one(text);
    expect(set.problems.map((p) => p.message)).toEqual(['1 draw with a zero-width aperture, drawn 0.1 mm wide']);
    expect(set.layers[0].boundsMm).toEqual({ x0: -0.5, y0: -0.5, x1: 5, y1: 0.5 });
    const outline = one(text, 'board-Edge_Cuts.gbr');
    expect(outline.problems).toEqual([]);
    expect(outline.layers[0].notes).toContain('1 draw with a zero-width aperture, drawn 0.1 mm wide');
  });

  it('never throws, whatever the text', () => {
    const pieces = ['%FSLAX46Y46*%', '%MOMM*%', '%MOIN*%', '%ADD10C,0.5*%', '%ADD11R,1X2*%', '%AMX*1,1,$1,0,0*%', '%ADD12X,0.3*%', 'D10*', 'D11*', 'D12*', 'D13*', 'G36*', 'G37*', 'G75*', 'G74*', 'G02*', 'G03*', '%LPC*%', '%LPD*%', '%SRX2Y2I1J1*%', '%SR*%', 'X100Y200D01*', 'X-5I3J4D01*', 'X0Y0D02*', 'X5Y5D03*', 'M48', 'INCH,TZ', 'METRIC', 'T1C0.8', 'T1', 'X1.5Y2', '%', 'M30', 'M02*', '*', 'X', '%AM', '%ABD12*%', '%AB*%', 'ÿ'];
    fc.assert(
      fc.property(fc.array(fc.constantFrom(...pieces), { maxLength: 30 }), fc.string(), (lines, noise) => {
        const set = one(lines.join('\n') + noise);
        for (const l of set.layers) expect(l.paints.length).toBeGreaterThan(0);
        expect(set.layers.length + set.problems.length + set.notes.length).toBeGreaterThan(0);
      }),
      { numRuns: 300 },
    );
  });
});

describe('Excellon formats, read by the library', () => {
  it.each([
    ['metric, leading zeros kept, every digit written', 'M48\nMETRIC,LZ,000.000\nT1C0.8\nT2C1.0\n%\nT1\nX012500Y005000\nT2\nX000100Y010000\nM30\n', [{ x: 12.5, y: 5, d: 0.8 }, { x: 0.1, y: 10, d: 1 }]],
    ['metric, leading zeros kept, trailing ones left out', 'M48\nMETRIC,LZ,000.000\nT1C0.8\n%\nT1\nX0125Y005\nM30\n', [{ x: 12.5, y: 5, d: 0.8 }]],
    ['metric, trailing zeros kept, leading ones left out', 'M48\nMETRIC,TZ,000.000\nT1C0.8\n%\nT1\nX12500Y5000\nM30\n', [{ x: 12.5, y: 5, d: 0.8 }]],
    ['inch, trailing zeros kept (2.4)', 'M48\nINCH,TZ\nT01C0.020\n%\nT01\nX3070Y2010\nM30\n', [{ x: 7.7978, y: 5.1054, d: 0.508 }]],
    ['inch, leading zeros kept (2.4)', 'M48\nINCH,LZ\nT01C0.020\n%\nT01\nX00307Y002\nM30\n', [{ x: 7.7978, y: 5.08, d: 0.508 }]],
    ['inch, Altium’s FILE_FORMAT=2:5', 'M48\n;FILE_FORMAT=2:5\nINCH,LZ\nT1F00S00C0.0354\n%\nT01\nX0120000Y0045\nM30\n', [{ x: 30.48, y: 11.43, d: 0.89916 }]],
    // Veribest's .ncd: units only after the header (M71), no zero suppression stated, the origin set with G93.
    ['Veribest: M71 after the header, a zero set that drills nothing', 'M48\nT01C.864\nT06C1.956\nR,H\n/\n%\nG90\nM71\nG93X000000Y000000\nG05\nT01\nX40500Y6270\nY3730\nT06\nX65539Y73500\nT00\nM30\n', [{ x: 40.5, y: 6.27, d: 0.864 }, { x: 40.5, y: 3.73, d: 0.864 }, { x: 65.539, y: 73.5, d: 1.956 }]],
    ['a zero set written short', 'M48\nMETRIC,TZ\nT1C0.8\n%\nG93X0Y0\nT1\nX12500Y5000\nM30\n', [{ x: 12.5, y: 5, d: 0.8 }]],
    ['metric with decimal points, KiCad putting the tool away with T0', 'M48\nFMAT,2\nMETRIC\nT1C0.400\n%\nG90\nG05\nT1\nX130.81Y-85.09\nT0\nM30\n', [{ x: 130.81, y: -85.09, d: 0.4 }]],
  ])('%s', (_, text, holes) => {
    expect(holesOf(text)).toEqual(holes);
    expect(one(text, 'board.drl').problems).toEqual([]);
  });
});

describe('an Excellon zero set that moves the origin', () => {
  it('is not applied, and says so', () => {
    const set = one('M48\nMETRIC,TZ\nT1C0.8\n%\nG93X1000Y0\nT1\nX12500Y5000\nM30\n', 'board.drl');
    expect(set.layers[0].holes).toEqual([{ x: 12.5, y: 5, diameterMm: 0.8 }]);
    expect(set.problems.map((p) => p.message)).toEqual([expect.stringMatching(/zero set \(G93\).*not applied/)]);
  });
});

describe('a board set as data', () => {
  it('survives structuredClone, so a worker can take it', () => {
    const set = one(gerber(`%ADD10C,0.5X0.2*%\nD10*\n${at(1, 1)}D03*\nG36*\n${at(0, 0)}D02*\nG01*\n${at(1, 0)}D01*\n${at(0, 1)}D01*\n${at(0, 0)}D01*\nG37*`));
    expect(structuredClone(set)).toEqual(set);
  });
});
