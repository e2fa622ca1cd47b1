import { describe, expect, it } from 'vitest';
import { guessLayerKind, guessLayerKinds } from './layer-kind';

describe('layer kind from the file name', () => {
  it.each([
    ['board-F_Cu.gbr', 'copper-top'],
    ['board-B_Cu.gbr', 'copper-bottom'],
    ['board-F_Mask.gbr', 'mask-top'],
    ['board-B_Mask.gbr', 'mask-bottom'],
    ['board-F_SilkS.gbr', 'silk-top'],
    ['board-B_Paste.gbr', 'paste-bottom'],
    ['board-Edge_Cuts.gbr', 'outline'],
    ['board-PTH.drl', 'drill'],
    ['SE_SG_IF_V2.GTL', 'copper-top'],
    ['SE_SG_IF_V2.GBS', 'mask-bottom'],
    ['SE_SG_IF_V2.GTO', 'silk-top'],
    ['SE_SG_IF_V2.GM1', 'outline'],
    ['rs232_cm.bot', 'copper-bottom'],
    ['thruhole.tap', 'drill'],
    ['board-In1_Cu.gbr', 'other'], // inner copper has no kind of its own
    ['notes.pdf', 'other'],
  ])('%s is %s', (name, kind) => expect(guessLayerKind(name)).toBe(kind));

  it('reads a whole set by its CAD tool’s conventions, name by name in order', () => {
    expect(guessLayerKinds(['x.GTL', 'x.GBL', 'x.GKO', 'x.XLN'])).toEqual(['copper-top', 'copper-bottom', 'outline', 'drill']);
  });
});
