// Stands in for lodash.fill in the browser build (app/vite.config.ts): the array's own fill, as
// gerber-plotter calls it (a new array of false). shims.test.ts holds it to lodash's answers.
module.exports = (array, value, start, end) => (array == null ? [] : array.fill(value, start, end));
