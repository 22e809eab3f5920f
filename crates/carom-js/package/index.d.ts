// The module is loaded when this package is imported; everything it exports is ready.
export * from "./carom_js.js";
