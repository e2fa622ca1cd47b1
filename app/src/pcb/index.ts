// Gerber and Excellon import: the studio loads this module with import() only, so the parser stays out of the first load.
export { guessLayerKind, guessLayerKinds, isCopper, LAYER_KINDS, type LayerKind } from './layer-kind';
export { problemsByFile, BoardUnreadable, type FileProblems } from './problem-words';
export { type KindSource } from './layer-content';
export { readBoard, type BoardFile, type BoardLayer, type BoardProblem, type BoardSet } from './read-board';
export {
  boardBounds,
  rasteriseBoard,
  DEFAULT_DRILL_DOT_MM,
  DEFAULT_THRESHOLD,
  LINES_PER_CELL,
  type BoardRaster,
  type DrillClear,
  type RasteriseOptions,
} from './rasterise';
export type { BoxMm, Paint, Shape } from './artwork';
export type { Orientation } from './orient';
export type { Hole } from './plot-to-artwork';
export { boardArtwork, boardFiles, boardSrc, boardWindow, markLayer, BOARD_SRC_PREFIX, MARK_HOLE_MM, MARK_OUTER_MM, type BoardArtwork, type BoardLook } from './board-artwork';
