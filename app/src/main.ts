// Mounts the app (its service worker is registered by App: pwa-update.svelte.ts), a task after the
// script's own: the bundle's parse and evaluation and the first screen's mount in one task were the
// page load's longest (issue 40).
import { mount } from 'svelte';
import App from './App.svelte';

setTimeout(() => mount(App, { target: document.getElementById('app')! }));
