// carom's entry: loads the WebAssembly module once, at import, from beside this file (Node
// reads it from disk; a browser or a bundler fetches it), so `import { World } from
// "carom-js"` is ready to use.
import init, { initSync } from "./carom_js.js";

export * from "./carom_js.js";

const wasm = new URL("./carom_js_bg.wasm", import.meta.url);
if (typeof process === "object" && process.versions?.node && wasm.protocol === "file:") {
    const { readFile } = await import("node:fs/promises");
    initSync({ module: await readFile(wasm) });
} else {
    await init({ module_or_path: wasm });
}
