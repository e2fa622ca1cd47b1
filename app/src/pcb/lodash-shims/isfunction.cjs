// Stands in for lodash.isfunction in the browser build (app/vite.config.ts). shims.test.ts holds it to lodash's answers.
module.exports = (value) => typeof value === 'function';
