// The TypeScript types: every class and function the module exports is declared, with every
// method, and every type a declaration names is declared too.
import { test } from "node:test";
import assert from "node:assert/strict";
import fs from "node:fs";
import path from "node:path";
import { carom, packageDir } from "./load.mjs";

const declarations = fs.readFileSync(path.join(packageDir, "carom_js.d.ts"), "utf8");
const manifest = JSON.parse(fs.readFileSync(path.join(packageDir, "package.json"), "utf8"));

test("the package's manifest points at its types and module", () => {
    assert.equal(manifest.types, "./index.d.ts");
    const entry = fs.readFileSync(path.join(packageDir, manifest.types), "utf8");
    assert.match(entry, /export \* from "\.\/carom_js\.js"/);
    for (const file of manifest.files.filter((f) => !f.endsWith("/"))) {
        assert.ok(fs.existsSync(path.join(packageDir, file)), `${file} is in the package`);
    }
});

test("every export has a declaration, and every class every method", () => {
    const exported = Object.keys(carom).filter((name) => name !== "initSync");
    assert.ok(exported.length >= 6);
    for (const name of exported) {
        const value = carom[name];
        const kind = /^class /.test(Function.prototype.toString.call(value)) ? "class" : "function";
        assert.match(declarations, new RegExp(`export (declare )?${kind} ${name}\\b`), `${kind} ${name} is declared`);
        if (kind !== "class") continue;
        const body = declarations.slice(declarations.indexOf(`class ${name}`));
        const members = body.slice(0, body.indexOf("\n}"));
        const methods = Object.getOwnPropertyNames(value.prototype)
            .concat(Object.getOwnPropertyNames(value))
            .filter((m) => !["constructor", "length", "name", "prototype", "__wrap", "__unwrap",
                "__destroy_into_raw", "__caromKey"].includes(m) && !m.startsWith("__wbg"));
        for (const method of methods) {
            assert.match(members, new RegExp(`\\b${method}\\b`), `${name}.${method} is declared`);
        }
    }
});

test("every type the declarations name is declared", () => {
    const declared = new Set([...declarations.matchAll(/export (?:declare )?(?:class|interface|type) (\w+)/g)].map((m) => m[1]));
    const builtins = new Set(["Float32Array", "Uint32Array", "Error", "Symbol", "Promise", "WebAssembly",
        "Response", "URL", "Request", "BufferSource", "RequestInfo", "InitInput", "InitOutput", "SyncInitInput",
        "Infinity", "Readonly", "Memory", "Module"]);
    const signatures = declarations.replace(/\/\*[\s\S]*?\*\//g, "").replace(/\/\/.*$/gm, "");
    const referenced = new Set([...signatures.matchAll(/[:|<(,]\s*(?:readonly\s+)?([A-Z]\w*)/g)].map((m) => m[1]));
    for (const name of referenced) {
        if (builtins.has(name)) continue;
        assert.ok(declared.has(name), `${name} is named but not declared`);
    }
});
