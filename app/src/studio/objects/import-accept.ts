// What the import's file picker offers: pictures and drawings, and the extensions CAD tools give Gerber and drill files.

/**
 * Gerber and Excellon extensions by the tools that write them: generic (gbr ger gbx grb pho art), KiCad and
 * Protel/Altium (gtl gbl gts gbs gto gbo gtp gbp gko gm1… gd1 gg1 gp1 g1…), Eagle (cmp sol stc sts plc pls crc
 * crs mil), OrCAD (top bot smt smb sst ssb spt spb drd tap), gEDA (cnc), Veribest and Mentor (gdo ncd), EasyEDA
 * Pro's drawings (gdd gdl), drill files (drl xln exc nc txt) and Visula (off).
 */
export const BOARD_EXTENSIONS: readonly string[] = (
  'gbr ger gbx grb pho art gdo ' +
  'gtl gbl gts gbs gto gbo gtp gbp gko gml gm1 gm2 gm3 gd1 gg1 gp1 gp2 gpt gpb g1 g2 g3 g4 ' +
  'cmp sol stc sts plc pls crc crs mil gdd gdl ' +
  'top bot smt smb sst ssb spt spb drd tap ' +
  'cnc ncd drl xln exc nc txt off'
).split(' ');

const PICTURES = 'image/svg+xml,.svg,image/png,image/jpeg,image/gif,image/bmp,image/webp';

/** The file input's accept list: a browser hides every other file until the user asks for all files. */
export const IMPORT_ACCEPT = `${PICTURES},${BOARD_EXTENSIONS.map((e) => `.${e}`).join(',')}`;
