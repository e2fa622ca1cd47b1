// What a board file is for (copper, mask, outline, drill…), guessed from its name by tracespace's whats-that-gerber.
import whatsThatGerber from 'whats-that-gerber';

export type LayerKind =
  | 'copper-top'
  | 'copper-bottom'
  | 'mask-top'
  | 'mask-bottom'
  | 'silk-top'
  | 'silk-bottom'
  | 'paste-top'
  | 'paste-bottom'
  | 'outline'
  | 'drill'
  | 'other';

export const LAYER_KINDS: readonly LayerKind[] = [
  'copper-top',
  'copper-bottom',
  'mask-top',
  'mask-bottom',
  'silk-top',
  'silk-bottom',
  'paste-top',
  'paste-bottom',
  'outline',
  'drill',
  'other',
];

export const isCopper = (kind: LayerKind): boolean => kind === 'copper-top' || kind === 'copper-bottom';

const SIDED: Record<string, string> = { copper: 'copper', soldermask: 'mask', silkscreen: 'silk', solderpaste: 'paste' };

function toKind(props: whatsThatGerber.GerberProps | undefined): LayerKind {
  if (!props?.type) return 'other';
  if (props.type === 'drill') return 'drill';
  if (props.type === 'outline') return 'outline';
  const sided = SIDED[props.type];
  // Inner copper and drawings have no kind of their own: the user says what they are.
  if (sided && (props.side === 'top' || props.side === 'bottom')) return `${sided}-${props.side}` as LayerKind;
  return 'other';
}

/** The kind one file name suggests; 'other' when the name says nothing. */
export function guessLayerKind(fileName: string): LayerKind {
  return toKind(whatsThatGerber([fileName])[fileName]);
}

/**
 * The kinds a whole board's file names suggest. whats-that-gerber looks at the names together, so a
 * set named by one CAD tool is read by that tool's conventions.
 */
export function guessLayerKinds(fileNames: readonly string[]): LayerKind[] {
  const props = whatsThatGerber([...new Set(fileNames)]);
  return fileNames.map((name) => toKind(props[name]));
}
