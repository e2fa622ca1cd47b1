// Mounts the app (its service worker is registered by App: pwa-update.svelte.ts).
import { mount } from 'svelte';
import App from './App.svelte';

mount(App, { target: document.getElementById('app')! });
