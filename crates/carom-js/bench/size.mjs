// What a user downloads: carom-js's WebAssembly module, the module gzipped (`gzip -9`'s level)
// and the tarball npm serves, beside Rapier's package (`@dimforge/rapier2d`, the one a bundler
// takes, at the version this bench pins). Prints the docs' table as CSV on standard output
// (`carom-bench measure` keeps it).
//
//   npm ci --prefix crates/carom-js/bench
//   node crates/carom-js/bench/size.mjs [--package target/carom-js/package]
//
// The tarballs' sizes are what `npm pack --dry-run` reports, so Rapier's is looked up in the
// npm registry.
import { execFileSync } from "node:child_process";
import fs from "node:fs";
import path from "node:path";
import zlib from "node:zlib";

let packageDir = "target/carom-js/package";
const args = process.argv.slice(2);
if (args.length === 2 && args[0] === "--package") {
    packageDir = args[1];
} else if (args.length) {
    console.error("usage: node crates/carom-js/bench/size.mjs [--package DIR]");
    process.exit(2);
}

/** The one `.wasm` file in `dir`. */
function moduleIn(dir) {
    const found = fs.readdirSync(dir).filter((name) => name.endsWith(".wasm"));
    if (found.length !== 1) throw new Error(`${dir} holds ${found.length} .wasm files, not one`);
    return path.join(dir, found[0]);
}

/** The tarball's bytes that `npm pack --dry-run` reports for `spec`, a folder or a package. */
function tarball(spec) {
    const report = JSON.parse(execFileSync("npm", ["pack", "--dry-run", "--json", spec], {
        cwd: import.meta.dirname,
        stdio: ["ignore", "pipe", "inherit"],
    }).toString());
    return report[0].size;
}

const megabytes = (bytes) => `${(bytes / 1e6).toFixed(2)} MB`;
const kilobytes = (bytes) => `${Math.round(bytes / 1e3)} kB`;

function row(name, wasm, spec) {
    const bytes = fs.readFileSync(wasm);
    const gzipped = zlib.gzipSync(bytes, { level: 9 }).length;
    return [name, megabytes(bytes.length), kilobytes(gzipped), kilobytes(tarball(spec))].join(",");
}

const carom = JSON.parse(fs.readFileSync(path.join(packageDir, "package.json"), "utf8"));
const rapierDir = path.join(import.meta.dirname, "node_modules", "@dimforge", "rapier2d");
const rapier = JSON.parse(fs.readFileSync(path.join(rapierDir, "package.json"), "utf8"));

console.log("package,module,gzipped,tarball");
console.log(row(`${carom.name} ${carom.version}`, moduleIn(packageDir), path.resolve(packageDir)));
console.log(row(`${rapier.name} ${rapier.version}`, moduleIn(rapierDir),
    `${rapier.name}@${rapier.version}`));
