// Which lines are work that keeps the machine to itself until answered: homing, the probe's, and those that change settings.

/** Which work a line is, for the rule (job/actions.ts): homing, the probe's lines, and those that change settings. */
export function lineWork(line: string): 'homing' | 'probing' | 'configuring' | null {
  if (/^G28\b/i.test(line)) return 'homing';
  if (/^(G29|G30|M401|M402|M280)(\s|$)/i.test(line)) return 'probing';
  if (/^(M500|M501|M502)(\s|$)/i.test(line) || /^M850\s+\S+\s+\S/i.test(line)) return 'configuring';
  return null;
}
