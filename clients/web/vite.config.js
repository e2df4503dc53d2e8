// Bundles the page into one directory that rbview serves as it is: no file is
// fetched from anywhere at run time (three.js and uPlot are in the bundle).
// The output directory comes from RBVIEW_OUT_DIR (CMake sets BUILD/clients/web/dist).
import { defineConfig } from "vite";

export default defineConfig({
  base: "./",
  build: {
    outDir: process.env.RBVIEW_OUT_DIR || "dist",
    emptyOutDir: true,
    chunkSizeWarningLimit: 2000,
    sourcemap: false,
  },
  logLevel: "warn",
});
