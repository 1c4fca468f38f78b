// Vitest runs the front end's unit tests, and only those: `npx vitest run`.
// (tests/wasm and tests/e2e are node:test suites; tests/native is ctest.)
import { defineConfig } from 'vitest/config';

export default defineConfig({
  test: {
    include: ['tests/web/**/*.test.ts'],
    environment: 'node',
  },
});
