import { describe, expect, it } from 'vitest';
import { BOARD_EXTENSIONS, IMPORT_ACCEPT } from './import-accept';

describe('the import picker’s file types', () => {
  it('offers every extension testers found hidden, and the ones offered before', () => {
    const offered = IMPORT_ACCEPT.split(',');
    const hidden = ['gbx', 'grb', 'cnc', 'top', 'bot', 'tap', 'gdo', 'ncd', 'gto', 'gbo', 'gtp', 'gbp'];
    const before = ['gbr', 'ger', 'gtl', 'gbl', 'gts', 'gbs', 'gko', 'gm1', 'gml', 'drl', 'xln', 'exc', 'txt', 'svg'];
    for (const e of [...hidden, ...before]) expect(offered, e).toContain(`.${e}`);
    expect(offered).toContain('image/png');
  });

  it('lists each extension once, in lower case, without its dot', () => {
    expect(new Set(BOARD_EXTENSIONS).size).toBe(BOARD_EXTENSIONS.length);
    for (const e of BOARD_EXTENSIONS) expect(e).toMatch(/^[a-z0-9]+$/);
  });
});
