// The halftones a picture can be exposed with, by name: what a project file may name (dither.ts makes them).

export type Halftone = 'semitones' | 'threshold' | 'floyd-steinberg' | 'atkinson' | 'jarvis' | 'stucki' | 'ordered';

export const HALFTONES: Halftone[] = ['semitones', 'threshold', 'floyd-steinberg', 'atkinson', 'jarvis', 'stucki', 'ordered'];
