// PADS Layout's CAM file names, which say nothing to whats-that-gerber and whose heads name no layer:
// art001.pho (routing layer 1), pgp002.pho (a plane), sm001021.pho (document layer 21, the top solder mask).
import type { LayerKind } from './layer-kind';

/** artNNN.pho / pgpNNN.pho: routing or plane layer NNN. */
const LAYER_FILE = /^(art|pgp)(\d{3})\.pho$/i;
/** A document layer's file: any prefix (sm, smd, sst, ssb, adt, adb, dd…), three digits, the document layer. */
const DOCUMENT_FILE = /^[a-z_]*(\d{3})(\d{3})\.pho$/i;

/**
 * PADS's document layers (21–30, or 121–130 in its 250-layer setup), by their number past the hundreds:
 * solder mask, paste mask, silkscreen and assembly drawing of each side, and the drill drawing.
 */
const DOCUMENT_KIND: Record<number, LayerKind> = {
  21: 'mask-top',
  22: 'paste-bottom',
  23: 'paste-top',
  24: 'other', // drill drawing
  25: 'other', // plane clearances
  26: 'silk-top',
  27: 'other', // assembly drawing, top
  28: 'mask-bottom',
  29: 'silk-bottom',
  30: 'other', // assembly drawing, bottom
};

/**
 * The kinds PADS's default names give, or null for a file not named so. Routing layer 1 is the top copper, the
 * highest routing layer of the set the bottom; the routing layers between them and the planes are inner
 * ('other'). The digits before a document layer's number do not say which routing layer is the bottom (a
 * published 4-layer board names its bottom mask sm002028.pho, an 8-layer one sm008028.pho), so they are not read.
 */
export function padsKinds(names: readonly string[]): (LayerKind | null)[] {
  let bottom = 0;
  for (const name of names) {
    const m = LAYER_FILE.exec(name);
    if (m && m[1].toLowerCase() === 'art') bottom = Math.max(bottom, Number(m[2]));
  }
  return names.map((name) => {
    const layer = LAYER_FILE.exec(name);
    if (layer) {
      const n = Number(layer[2]);
      if (layer[1].toLowerCase() === 'pgp') return 'other';
      return n === 1 ? 'copper-top' : n === bottom ? 'copper-bottom' : 'other';
    }
    const doc = DOCUMENT_FILE.exec(name);
    return doc ? (DOCUMENT_KIND[Number(doc[2]) % 100] ?? null) : null;
  });
}
