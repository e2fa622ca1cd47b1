// Stands in for lodash.padend in the browser build (app/vite.config.ts): the string's own padEnd, as
// gerber-parser calls it (a coordinate's digits, a width, '0'). shims.test.ts holds it to lodash's answers.
module.exports = (string, length, chars) => String(string ?? '').padEnd(length, chars ?? ' ');
