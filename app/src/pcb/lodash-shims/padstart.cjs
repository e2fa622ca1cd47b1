// Stands in for lodash.padstart in the browser build (app/vite.config.ts): the string's own padStart, as
// gerber-parser calls it (a coordinate's digits, a width, '0'). shims.test.ts holds it to lodash's answers.
module.exports = (string, length, chars) => String(string ?? '').padStart(length, chars ?? ' ');
