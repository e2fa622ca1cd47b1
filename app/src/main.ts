// Mounts the app, and registers its service worker.
import { mount } from 'svelte';
import App from './App.svelte';

mount(App, { target: document.getElementById('app')! });

// Installable and offline: the service worker keeps the app's files (not in development, where
// Vite serves them fresh).
if (import.meta.env.PROD && 'serviceWorker' in navigator) void navigator.serviceWorker.register('/sw.js');
