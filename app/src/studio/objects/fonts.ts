// The fonts the text tool offers: the generic families every browser has, and, where the browser
// can list them (Chromium's Local Font Access, which asks the user first), the installed ones.

export const GENERIC_FONTS = ['sans-serif', 'serif', 'monospace', 'system-ui'];

interface LocalFont {
  family: string;
}

export function canListFonts(): boolean {
  return typeof window !== 'undefined' && 'queryLocalFonts' in window;
}

/** The installed families, each once, sorted; empty when refused or not available. */
export async function installedFonts(): Promise<string[]> {
  if (!canListFonts()) return [];
  try {
    const fonts = await (window as unknown as { queryLocalFonts(): Promise<LocalFont[]> }).queryLocalFonts();
    return [...new Set(fonts.map((f) => f.family))].sort((a, b) => a.localeCompare(b));
  } catch {
    return [];
  }
}
