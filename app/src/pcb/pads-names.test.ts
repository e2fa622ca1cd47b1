// PADS Layout's CAM names, as three published PADS boards have them (an 8-layer, a 4-layer, a 2-layer in PADS's
// 250-layer numbering), and a 2-layer set written by hand in PADS's form read whole.
import { describe, expect, it } from 'vitest';
import { padsKinds } from './pads-names';
import { readBoard } from './read-board';
import { at, gerber } from './test-boards';

const kinds = (names: string[]) => Object.fromEntries(names.map((n, i) => [n, padsKinds(names)[i]]));

describe('PADS’s CAM names', () => {
  it('8 layers (BerkeleyLab’s Zest): layer 1 top, layer 8 bottom, planes and inner routing inner', () => {
    const names = ['art001.pho', 'art003.pho', 'art005.pho', 'art008.pho', 'pgp002.pho', 'pgp007.pho', 'sm001021.pho', 'sm008028.pho', 'smd001023.pho', 'sst001026.pho', 'dd001024.pho'];
    expect(kinds(names)).toEqual({
      'art001.pho': 'copper-top',
      'art003.pho': 'other',
      'art005.pho': 'other',
      'art008.pho': 'copper-bottom',
      'pgp002.pho': 'other',
      'pgp007.pho': 'other',
      'sm001021.pho': 'mask-top',
      'sm008028.pho': 'mask-bottom',
      'smd001023.pho': 'paste-top',
      'sst001026.pho': 'silk-top',
      'dd001024.pho': 'other',
    });
  });

  it('PADS’s 250-layer numbering (document layers 121–130): the same kinds', () => {
    const names = ['art001.pho', 'art002.pho', 'sm001121.pho', 'sm002128.pho', 'smd001123.pho', 'smd002122.pho', 'adt001127.pho', 'adb002130.pho', 'dd001124.pho'];
    expect(kinds(names)).toEqual({
      'art001.pho': 'copper-top',
      'art002.pho': 'copper-bottom',
      'sm001121.pho': 'mask-top',
      'sm002128.pho': 'mask-bottom',
      'smd001123.pho': 'paste-top',
      'smd002122.pho': 'paste-bottom',
      'adt001127.pho': 'other',
      'adb002130.pho': 'other',
      'dd001124.pho': 'other',
    });
  });

  it('4 layers (akkdong’s MiniVario): the highest routing layer is the bottom, though the bottom’s document files say 002', () => {
    const names = ['art001.pho', 'pgp002.pho', 'art003.pho', 'art004.pho', 'sm001021.pho', 'sm002028.pho', 'smd002022.pho', 'ssb002029.pho', 'dd002024.pho'];
    expect(kinds(names)).toEqual({
      'art001.pho': 'copper-top',
      'pgp002.pho': 'other',
      'art003.pho': 'other',
      'art004.pho': 'copper-bottom',
      'sm001021.pho': 'mask-top',
      'sm002028.pho': 'mask-bottom',
      'smd002022.pho': 'paste-bottom',
      'ssb002029.pho': 'silk-bottom',
      'dd002024.pho': 'other',
    });
  });

  it('the highest routing layer is the bottom; a lone layer 1 is the top', () => {
    expect(kinds(['art001.pho', 'art004.pho', 'art002.pho', 'sst001026.pho'])).toEqual({ 'art001.pho': 'copper-top', 'art004.pho': 'copper-bottom', 'art002.pho': 'other', 'sst001026.pho': 'silk-top' });
    expect(kinds(['art001.pho'])).toEqual({ 'art001.pho': 'copper-top' });
  });

  it('says nothing of other names', () => {
    expect(padsKinds(['top.pho', 'board-F_Cu.gbr', 'art1.pho', 'sm001021.gbr'])).toEqual([null, null, null, null]);
  });

  it('a PADS set read whole: each file its kind from its name, and nothing guessed from what it draws', () => {
    // PADS's head names no layer ("G04 Layer Name board.pcb - circuitry"): only the file's name says it.
    const pads = (body: string) => gerber(`G04 PADS VX.1.2 generated Gerber (RS-274-X) file*\nG04 Layer Name board.pcb - circuitry*\n${body}`);
    const pad = (x: number) => `${at(x, 2)}D03*`;
    const copper = pads(`%ADD10C,1.6*%\n%ADD11C,0.25*%\nD10*\n${[2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22].map(pad).join('\n')}\nD11*\n${at(2, 2)}D02*\n${at(22, 2)}D01*`);
    const set = readBoard([
      { name: 'art001.pho', text: copper },
      { name: 'art002.pho', text: copper },
      { name: 'sm001021.pho', text: pads(`%ADD12C,1.8*%\nD12*\n${pad(2)}`) },
      { name: 'sst001026.pho', text: pads(`%ADD13C,0.15*%\nD13*\n${at(1, 1)}D02*\n${at(5, 1)}D01*`) },
      { name: 'drl001.drl', text: 'M48\nMETRIC\nT1C0.8\n%\nT1\nX2.0Y2.0\nM30\n' },
    ]);
    expect(Object.fromEntries(set.layers.map((l) => [l.file, [l.kind, l.kindFrom]]))).toEqual({
      'art001.pho': ['copper-top', 'name'],
      'art002.pho': ['copper-bottom', 'name'],
      'sm001021.pho': ['mask-top', 'name'],
      'sst001026.pho': ['silk-top', 'name'],
      'drl001.drl': ['drill', 'content'],
    });
    expect(set.problems).toEqual([]);
  });
});
