// Stands in for lodash.isfinite in the browser build (app/vite.config.ts): a finite number, not a string of one.
// shims.test.ts holds it to lodash's answers.
module.exports = (value) => Number.isFinite(value);
