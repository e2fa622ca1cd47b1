// What a board file is, from what it says about itself: its X2 file function, the words of its name and of
// the comments old CAD tools write (gEDA's title, Veribest's layer name), and, failing those, whether it
// draws as copper does (pads flashed and tracks drawn between them).
import { guessLayerKinds, type LayerKind } from './layer-kind';
import { padsKinds } from './pads-names';
import type { PlotObject } from './tracespace';

/** How a kind was found, strongest first. 'content': from what the file is (Excellon) or draws (copper's pads and tracks). */
export type KindSource = 'attribute' | 'name' | 'comment' | 'content' | 'none';

export interface KindGuess {
  kind: LayerKind;
  from: KindSource;
}

/** Only the head of a file carries its attributes and the CAD tool's comments. */
const HEAD_CHARS = 4096;

/**
 * Gerber X2's file function, as an extended command (%TF.FileFunction,Copper,L1,Top*%) or as KiCad and others
 * write it into a comment for older readers (G04 #@! TF.FileFunction,Copper,L1,Top*).
 */
export function kindFromAttributes(text: string): LayerKind | null {
  const m = /(?:%|G04 #@! )TF\.FileFunction,([^*%\r\n]*)/.exec(text.slice(0, HEAD_CHARS));
  if (!m) return null;
  const [what, ...rest] = m[1].split(',').map((v) => v.trim().toLowerCase());
  const side = rest.includes('top') ? 'top' : rest.includes('bot') ? 'bottom' : null;
  switch (what) {
    case 'copper':
      return side ? `copper-${side}` : 'other'; // Inr: an inner layer has no kind of its own
    case 'soldermask':
      return side ? `mask-${side}` : 'other';
    case 'legend':
      return side ? `silk-${side}` : 'other';
    case 'paste':
      return side ? `paste-${side}` : 'other';
    case 'profile':
      return 'outline';
    case 'plated':
    case 'nonplated':
      return 'drill';
    default:
      return 'other'; // drawings, drill maps, keep-outs, glue…: said outright, and none of them is exposed
  }
}

/** Words that name a drawing for people, never artwork to expose (wins over a side named with it: AssemblyTop). */
const DRAWING = /\b(?:assembl\w*|assy|fab|fabrication|drawing|drill ?map|courtyard|doc\w*|notes?|drd)\b/;
// Not gEDA's "group N": a group of layers may be an outer one.
const INNER = /\b(?:inner|in \d+|inr|gnd|ground|power|pwr|plane|vcc)\b/;
const TOP = /\b(?:component|comp|cmp|top|front)\b/;
const BOTTOM = /\b(?:solder|sol|bottom|bot|back)\b/;

/** Lower-case words: camelCase, run-together gEDA names ("componentmask") and numbers split apart. */
function wordsOf(text: string): string {
  return text
    .replace(/([a-z0-9])([A-Z])/g, '$1 $2')
    .toLowerCase()
    .replace(/(mask|silk|paste)/g, ' $1 ')
    .replace(/[^a-z0-9]+/g, ' ')
    .replace(/([a-z])(\d)/g, '$1 $2')
    .trim();
}

/** A drawing for people, by its name or extension (OrCAD's .drd is its drill drawing). */
export const isDrawingName = (name: string): boolean => DRAWING.test(wordsOf(name));

/** The side a name gives: "component side" before a bare "solder" (gEDA's "solder mask component side"). */
function sideOf(words: string): 'top' | 'bottom' | null {
  const said = /\b(component|comp|top|front|solder|bottom|back) side\b/.exec(words);
  if (said) return /^(?:component|comp|top|front)$/.test(said[1]) ? 'top' : 'bottom';
  if (TOP.test(words)) return 'top';
  if (BOTTOM.test(words)) return 'bottom';
  return null;
}

/**
 * The kind the words of a name or comment give, in the conventions of tools whats-that-gerber does not know:
 * gEDA PCB (front, back, frontmask, componentsilk, solder, group1), Eagle (top-cop), Veribest (EtchLayer2Bottom).
 */
export function kindFromWords(text: string, sideAlone = true): LayerKind | null {
  const words = wordsOf(text);
  if (DRAWING.test(words)) return 'other';
  const side = sideOf(words);
  // Without a side these are still not copper: 'other', so no guess from what they draw takes them for it.
  // Paste before mask: EasyEDA calls its paste layer "TopPasteMaskLayer".
  if (/\b(?:paste|cream|stencil)\b/.test(words)) return side ? `paste-${side}` : 'other';
  if (/\b(?:mask|stop|resist)\b/.test(words)) return side ? `mask-${side}` : 'other';
  if (/\b(?:silk|legend|overlay|sieb)\b/.test(words)) return side ? `silk-${side}` : 'other';
  if (/\b(?:outline|profile|edge|edges|contour|dimension)\b/.test(words)) return 'outline';
  if (INNER.test(words)) return 'other';
  if (/\b(?:copper|cop|cu|etch|signal|conductor)\b/.test(words)) return side ? `copper-${side}` : null;
  // gEDA names its outer copper by the side alone ("board.front.gbr", "%LNBACK*%", "Title: …, component").
  return side && sideAlone ? `copper-${side}` : null;
}

/** What Allegro's film record lists besides the artwork: marks on every film, which say nothing of its kind. */
const ALLEGRO_ON_EVERY_FILM = /^(?:TOOLING_CORNERS|TITLE_BLOCK|ROOT_NUMBER|PLATING_BAR|LYR_.*|DISPLAY_.*)$/;
/** Subclasses only drawings for people hold: assembly, fabrication, dimensions, drill legends and charts. */
const ALLEGRO_DRAWING = /ASSEMBLY|ASSY|FAB|DIMENSION|NCLEGEND|NCDRILL|XSECTION/;

/**
 * Cadence Allegro's film record: one "G04 Layer:  CLASS/SUBCLASS*" line per layer the film gathers (ETCH/TOP,
 * PIN/SOLDERMASK_TOP, REF DES/SILKSCREEN_BOTTOM, BOARD GEOMETRY/OUTLINE…), every film with tooling corners and a
 * title block too. Its copper is etch on an outer side; a mask, paste or legend film says so in its subclasses,
 * a drawing in its assembly, fabrication, dimension or drill-legend ones, and the more of them win; a film with
 * nothing but the board's outline is the outline.
 */
export function kindFromAllegroFilm(head: string): LayerKind | null {
  const layers = [...head.matchAll(/^G04 Layer:\s+([A-Z][A-Z ]*)\/([^*\r\n]+)\*/gm)]
    .map((m) => ({ cls: m[1].trim(), sub: m[2].trim() }))
    .filter((l) => !ALLEGRO_ON_EVERY_FILM.test(l.sub));
  if (layers.length === 0) return null;
  const side = (s: string) => (s === 'TOP' ? 'top' : 'bottom');
  for (const { cls, sub } of layers) if (cls === 'ETCH') return sub === 'TOP' || sub === 'BOTTOM' ? `copper-${side(sub)}` : 'other';
  // A legend film holds an assembly layer or two, and an assembly drawing the auto-silk (OrCAD PCB Designer's
  // Assembly.art): the kind most of its layers name wins, a drawing on a tie.
  const votes = new Map<LayerKind, number>();
  for (const { sub } of layers) {
    const m = /^(SOLDERMASK|PASTEMASK|SILKSCREEN|AUTOSILK)_(TOP|BOTTOM)$/.exec(sub);
    const kind: LayerKind | undefined = m ? `${m[1] === 'SOLDERMASK' ? 'mask' : m[1] === 'PASTEMASK' ? 'paste' : 'silk'}-${side(m[2])}` : undefined;
    if (kind) votes.set(kind, (votes.get(kind) ?? 0) + 1);
  }
  const drawings = layers.filter((l) => l.cls === 'DRAWING FORMAT' || ALLEGRO_DRAWING.test(l.sub)).length;
  const [kind, most] = [...votes].reduce((a, b) => (b[1] > a[1] ? b : a), ['other' as LayerKind, 0]);
  if (most > drawings) return kind;
  if (drawings > 0) return 'other';
  if (layers.every((l) => l.cls === 'BOARD GEOMETRY' && /^(?:DESIGN_)?OUTLINE$/.test(l.sub))) return 'outline';
  return 'other';
}

/**
 * What CAD tools say of the layer in the file's head: Allegro's film record, gEDA's title and layer name (%LN),
 * Veribest's, EasyEDA's and Copper Connection's "G04 Layer: TopSilkscreenLayer", Eagle's image name (%IN).
 */
export function kindFromComments(text: string): LayerKind | null {
  const head = text.slice(0, HEAD_CHARS);
  const film = kindFromAllegroFilm(head);
  if (film) return film;
  const said = [
    // The image's layer name: gEDA's "%LNFRONT*%", "%LNBOTTOM*%". Before gEDA's title, which names the layer
    // as its user did ("controller, bottomVCC" is the bottom copper, not an inner VCC plane).
    /%LN([^*%]*)\*%/,
    /^G04 Title: [^,\r\n]*, ([^*\r\n]*)\*/m, // gEDA PCB: "G04 Title: (unknown), component *"
    /^G04 Layer\s*: ([^*\r\n]*)\*/m, // Veribest: "G04 Layer : EtchLayer2Bottom.gdo*"
  ];
  for (const re of said) {
    const m = re.exec(head);
    const kind = m ? kindFromWords(m[1].replace(/\.\w+$/, '')) : null;
    if (kind) return kind;
  }
  // The image's name: Eagle 9 writes its layer's ("%INSilkscreen Top*%", "%INTop Copper*%"), other tools the
  // project's, so only a layer's word counts here, never a side alone ("%INFrontPanel*%" is no copper).
  const image = /%IN([^*%]*)\*%/.exec(head);
  return image ? kindFromWords(image[1], false) : null;
}

/** A name without its extension, whose letters would read as words ("x.sol" is not "solder"). */
const stem = (name: string) => name.replace(/\.[^.]*$/, '');

/**
 * Every file's kind and how it was found: its X2 attribute; the layer its CAD tool names in its head (%LN,
 * "G04 Layer:"): what a file says of itself beats what it is called ("top.grb" whose head says "top silk");
 * a drawing named as such; PADS's CAM names (art001.pho, sm001021.pho); whats-that-gerber's reading of the
 * whole set's names (KiCad, Protel, Altium, Eagle, OrCAD extensions); the name's words.
 */
export function guessKinds(files: readonly { name: string; text: string }[]): KindGuess[] {
  let byName: LayerKind[];
  try {
    byName = guessLayerKinds(files.map((f) => f.name));
  } catch {
    byName = files.map(() => 'other'); // a name whats-that-gerber chokes on says nothing about the file
  }
  const pads = padsKinds(files.map((f) => f.name));
  return files.map((f, i) => {
    const attribute = kindFromAttributes(f.text);
    if (attribute) return { kind: attribute, from: 'attribute' };
    const comment = kindFromComments(f.text);
    if (comment) return { kind: comment, from: 'comment' };
    if (isDrawingName(f.name)) return { kind: 'other', from: 'name' };
    const padsKind = pads[i];
    if (padsKind) return { kind: padsKind, from: 'name' };
    if (byName[i] !== 'other') return { kind: byName[i], from: 'name' };
    const words = kindFromWords(stem(f.name));
    if (words) return { kind: words, from: 'name' };
    return { kind: 'other', from: 'none' };
  });
}

/** What a layer draws, counted: the mix that tells copper from a mask, a legend or an outline. */
export interface DrawingMix {
  /** Apertures flashed: pads. */
  flashes: number;
  /** Straight and curved pieces drawn with an aperture: tracks, or a legend's letters. */
  segments: number;
  /** Different widths those are drawn with. */
  widths: number;
  /** Regions filled: pours. */
  regions: number;
}

export function drawingMix(objects: readonly PlotObject[]): DrawingMix {
  const mix = { flashes: 0, segments: 0, widths: 0, regions: 0 };
  const widths = new Set<number>();
  for (const o of objects) {
    if (o.type === 'pad') mix.flashes++;
    else if (o.type === 'fill') mix.regions++;
    else if (o.type === 'stroke') {
      mix.segments += o.path.length;
      widths.add(o.width);
    }
  }
  mix.widths = widths.size;
  return mix;
}

/**
 * Pads with tracks between them, or with poured regions: copper. A mask flashes pads and draws little; a legend
 * or an outline draws but flashes little; tracks come in more than one width (a mask's few strokes in one).
 */
export function looksLikeCopper(m: DrawingMix): boolean {
  if (m.flashes < 10) return false;
  const tracks = m.segments >= m.flashes / 4 && m.widths >= 2;
  const pours = m.regions >= 10;
  return tracks || pours;
}
