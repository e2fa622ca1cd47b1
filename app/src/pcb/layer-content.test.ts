import { describe, expect, it } from 'vitest';
import { drawingMix, guessKinds, isDrawingName, kindFromAllegroFilm, kindFromAttributes, kindFromComments, kindFromWords, looksLikeCopper } from './layer-content';
import { plotFile } from './tracespace';
import { at, gerber } from './test-boards';

describe('a file’s X2 file function', () => {
  it.each([
    ['%TF.FileFunction,Copper,L1,Top*%', 'copper-top'],
    ['%TF.FileFunction,Copper,L2,Bot*%', 'copper-bottom'],
    ['%TF.FileFunction,Copper,L2,Inr*%', 'other'],
    ['%TF.FileFunction,Copper,L4,Bot,Signal*%', 'copper-bottom'],
    ['%TF.FileFunction,Soldermask,Top*%', 'mask-top'],
    ['%TF.FileFunction,Legend,Bot*%', 'silk-bottom'],
    ['%TF.FileFunction,Paste,Top*%', 'paste-top'],
    ['%TF.FileFunction,Profile,NP*%', 'outline'],
    ['%TF.FileFunction,Plated,1,2,PTH*%', 'drill'],
    ['%TF.FileFunction,AssemblyDrawing,Top*%', 'other'],
    ['G04 #@! TF.FileFunction,Copper,L1,Top*', 'copper-top'], // KiCad's X2 in a comment, for X1 readers
  ])('%s is %s', (line, kind) => expect(kindFromAttributes(`G04 header*\n${line}\n%FSLAX46Y46*%\n`)).toBe(kind));

  it('is nothing when the file has none', () => expect(kindFromAttributes('%FSLAX46Y46*%\n%MOMM*%\n')).toBeNull());
});

describe('the words of a name or a comment', () => {
  it.each([
    ['hellboard.front', 'copper-top'], // gEDA PCB
    ['hellboard.back', 'copper-bottom'],
    ['hellboard.frontmask', 'mask-top'],
    ['board.backsilk', 'silk-bottom'],
    ['numpres.pcb.output_componentmask', 'mask-top'],
    ['numpres.pcb.output_soldermask', 'mask-bottom'],
    ['solder mask component side', 'mask-top'], // gEDA's old title: the side said outright wins over "solder"
    ['silkscreen component side', 'silk-top'],
    ['component', 'copper-top'],
    ['solder', 'copper-bottom'],
    ['top-cop', 'copper-top'], // Eagle
    ['EtchLayer2Bottom', 'copper-bottom'], // Veribest
    ['AssemblyTop', 'other'], // a drawing, whatever side it names
    ['hellboard.fab', 'other'],
    ['ground', 'other'],
    ['sieb0', 'other'], // a legend ("Siebdruck") without a side is still not copper
    ['board.outline', 'outline'],
    ['artwork_1', null],
    ['l1-orig', null],
    ['laptop-backlight', null],
  ])('%s is %s', (words, kind) => expect(kindFromWords(words)).toBe(kind));

  it('knows drawings by name or extension', () => {
    expect(['AssemblyTop.gdo', 'board-F_Fab.gbr', 'rs232_cm.drd', 'hellboard.fab.gbr'].every(isDrawingName)).toBe(true);
    expect(['board-F_Cu.gbr', 'top-cop.gbx', 'fabulous.gbr'].some(isDrawingName)).toBe(false);
  });

  it('reads the layer old CAD tools name in their comments', () => {
    expect(kindFromComments('G04 start of page 2 for group 0 idx 0\nG04 Title: (unknown), component *\n%MOIN*%')).toBe('copper-top');
    expect(kindFromComments('*\nG04 Layer : EtchLayer2Bottom.gdo*\n%MOIN*%')).toBe('copper-bottom');
    expect(kindFromComments('G04 Layer : SolderPasteBottom.gdo*\n')).toBe('paste-bottom');
    expect(kindFromComments('%MOIN*%\n%LNBACK*%\n')).toBe('copper-bottom');
    expect(kindFromComments('G04 Title: test, layergroup #1 *\n%LNGROUP_0*%\n')).toBeNull();
    // gEDA's layer name is its group's own; the title's is the user's (stepper-lights' controller board, in gerbonara).
    expect(kindFromComments('G04 start of page 3 for group 1 idx 2 *\nG04 Title: controller, bottomVCC *\n%MOIN*%\n%FSLAX25Y25*%\n%LNBOTTOM*%\n')).toBe('copper-bottom');
    expect(kindFromComments('G04 Title: controller, jumper *\n%LNGROUP3*%\n')).toBeNull();
  });

  // Eagle 9 names the layer in the image name; other tools put the project's name there.
  it.each([
    ['%INTop Copper*%', 'copper-top'],
    ['%INSilkscreen Top*%', 'silk-top'], // whats-that-gerber takes silkscreen_top.gbr for the top copper
    ['%INSoldermask Top*%', 'mask-top'],
    ['%INSolderpaste Bottom*%', 'paste-bottom'],
    ['%INProfile*%', 'outline'],
    ['%INFrontPanel*%', null], // a side alone in a project's name is no copper
    ['%INPCB1*%', null],
  ])('reads Eagle’s image name %s as %s', (line, kind) => {
    expect(kindFromComments(`G04 EAGLE Gerber RS-274X export*\nG75*\n%MOMM*%\n%FSLAX34Y34*%\n%LPD*%\n${line}\n%IPPOS*%\n`)).toBe(kind);
  });

  // The film records of gerbonara's Allegro boards (Cadence Allegro 16.6 and 17.2), as each film's head lists them.
  const film = (...layers: string[]) =>
    `G04 ================== begin FILE IDENTIFICATION RECORD ==================*\nG04 File Origin:  Cadence Allegro 17.2-060*\nG04 *\n${layers.map((l) => `G04 Layer:  ${l}*`).join('\n')}\nG04 *\n`;
  it.each([
    [film('VIA CLASS/TOP', 'PIN/TOP', 'ETCH/TOP', 'PACKAGE GEOMETRY/ETCH_TOP', 'BOARD GEOMETRY/LYR_TOP', 'BOARD GEOMETRY/TOOLING_CORNERS'), 'copper-top'],
    [film('VIA CLASS/BOTTOM', 'PIN/BOTTOM', 'ETCH/BOTTOM', 'BOARD GEOMETRY/ROOT_NUMBER'), 'copper-bottom'],
    [film('BOARD GEOMETRY/TOOLING_CORNERS', 'VIA CLASS/GND2', 'PIN/GND2', 'ETCH/GND2', 'DRAWING FORMAT/TITLE_BLOCK'), 'other'],
    [film('VIA CLASS/SOLDERMASK_TOP', 'PIN/SOLDERMASK_TOP', 'BOARD GEOMETRY/TOOLING_CORNERS'), 'mask-top'],
    [film('BOARD GEOMETRY/TOOLING_CORNERS', 'USER PART NUMBER/DISPLAY_BOTTOM', 'PIN/PASTEMASK_BOTTOM', 'DRAWING FORMAT/TITLE_BLOCK'), 'paste-bottom'],
    // Its first layer names a side and no layer: read as words, it was taken for the bottom copper.
    [film('PACKAGE GEOMETRY/DISPLAY_BOTTOM', 'MANUFACTURING/AUTOSILK_BOTTOM', 'BOARD GEOMETRY/TOOLING_CORNERS', 'REF DES/SILKSCREEN_BOTTOM'), 'silk-bottom'],
    // Fabrication and assembly drawings hold the outline among their layers: they were taken for the outline.
    [film('BOARD GEOMETRY/DESIGN_OUTLINE', 'DRAWING FORMAT/DSIZE', 'BOARD GEOMETRY/FAB_NOTES2', 'MANUFACTURING/NCLEGEND-1-4', 'BOARD GEOMETRY/OUTLINE', 'BOARD GEOMETRY/DIMENSION'), 'other'],
    [film('BOARD GEOMETRY/DESIGN_OUTLINE', 'REF DES/ASSEMBLY_TOP', 'PACKAGE GEOMETRY/ASSEMBLY_TOP', 'BOARD GEOMETRY/OUTLINE'), 'other'],
    [film('BOARD GEOMETRY/OUTLINE', 'BOARD GEOMETRY/TOOLING_CORNERS'), 'outline'],
    // OrCAD PCB Designer (Allegro 17.4): an assembly film gathers the auto-silk among keep-outs and drill legends.
    [film('ROUTE KEEPOUT/TOP', 'MANUFACTURING/NCDRILL_LEGEND', 'MANUFACTURING/AUTOSILK_TOP', 'MANUFACTURING/XSECTION_CHART', 'BOARD GEOMETRY/DIMENSION'), 'other'],
    [film('VIA KEEPOUT/TOP', 'VIA CLASS/TOP', 'PIN/FILMMASKBOTTOM', 'PIN/TOP', 'ETCH/TOP', 'BOARD GEOMETRY/OUTLINE'), 'copper-top'],
    [film('VIA KEEPOUT/ALL', 'PIN/LAYER 1', 'ETCH/LAYER 1', 'BOARD GEOMETRY/OUTLINE'), 'other'],
    // …and its bottom legend an assembly layer among its legends.
    [film('REF DES/SILKSCREEN_BOTTOM', 'PACKAGE GEOMETRY/ASSEMBLY_BOTTOM', 'PACKAGE GEOMETRY/SILKSCREEN_BOTTOM', 'BOARD GEOMETRY/SILKSCREEN_BOTTOM'), 'silk-bottom'],
  ])('reads an Allegro film record (%#) as %s', (head, kind) => {
    expect(kindFromAllegroFilm(head)).toBe(kind);
    expect(kindFromComments(head)).toBe(kind);
  });

  it('leaves a Veribest layer name, which has no class, to the name’s words', () => {
    expect(kindFromAllegroFilm('*\nG04 Layer : EtchLayer2Bottom.gdo*\n')).toBeNull();
  });
});

describe('a board’s kinds, strongest clue first', () => {
  const copper = '%TF.FileFunction,Copper,L1,Top*%\n%FSLAX46Y46*%\n';
  it('takes an attribute over a name, a drawing’s name over whats-that-gerber, its reading over the name’s words', () => {
    expect(guessKinds([
      { name: 'odd.gbr', text: copper },
      { name: 'AssemblyTop.gdo', text: '' }, // whats-that-gerber would say top copper
      { name: 'board-F_Fab.gbr', text: '' }, // whats-that-gerber would say drill
      { name: 'x.GTL', text: '' },
      { name: 'hellboard.front.gbr', text: '' },
      { name: 'artwork_1.grb', text: 'G04 Title: (unknown), solder *\n' },
      { name: 'artwork_2.grb', text: '%FSLAX33Y33*%\n' },
    ])).toEqual([
      { kind: 'copper-top', from: 'attribute' },
      { kind: 'other', from: 'name' },
      { kind: 'other', from: 'name' },
      { kind: 'copper-top', from: 'name' },
      { kind: 'copper-top', from: 'name' },
      { kind: 'copper-bottom', from: 'comment' },
      { kind: 'other', from: 'none' },
    ]);
  });
});

describe('what a layer draws', () => {
  const pads = (n: number) => Array.from({ length: n }, (_, i) => `${at(i * 2, 0)}D03*`).join('\n');
  const tracks = (n: number, width: string) => `%ADD1${width.length}C,${width}*%\nD1${width.length}*\n` + Array.from({ length: n }, (_, i) => `${at(i * 2, 0)}D02*\n${at(i * 2, 1)}D01*`).join('\n');
  const mixOf = (body: string) => drawingMix(plotFile(gerber(body), 'gerber').objects);

  it('counts flashes, drawn pieces, their widths and regions', () => {
    expect(mixOf(`%ADD10C,1*%\nD10*\n${pads(3)}\n${tracks(2, '0.2')}`)).toEqual({ flashes: 3, segments: 2, widths: 1, regions: 0 });
  });

  it('calls pads with tracks of several widths copper; a mask, a legend or too little is not', () => {
    const copper = mixOf(`%ADD10C,1*%\nD10*\n${pads(20)}\n${tracks(5, '0.2')}\n${tracks(3, '0.25')}`);
    expect(looksLikeCopper(copper)).toBe(true);
    expect(looksLikeCopper({ flashes: 85, segments: 0, widths: 0, regions: 0 })).toBe(false); // a mask
    expect(looksLikeCopper({ flashes: 209, segments: 110, widths: 1, regions: 0 })).toBe(false); // a mask with a few strokes
    expect(looksLikeCopper({ flashes: 1, segments: 1079, widths: 4, regions: 0 })).toBe(false); // a legend
    expect(looksLikeCopper({ flashes: 360, segments: 0, widths: 0, regions: 1845 })).toBe(true); // gEDA's poured copper
    expect(looksLikeCopper({ flashes: 6, segments: 2042, widths: 5, regions: 0 })).toBe(false); // an assembly drawing
  });
});
