// What a browser downloads to open the demo: each file of the site as `build-site.sh` writes
// it, and gzipped at `gzip -9`'s level, as a server that compresses would send it. Prints the
// docs' table as CSV on standard output (`carom-bench measure` keeps it).
//
//   node crates/carom-web/test/download-size.mjs [--site target/web]
import fs from "node:fs";
import path from "node:path";
import zlib from "node:zlib";

let site = "target/web";
const args = process.argv.slice(2);
if (args.length === 2 && args[0] === "--site") {
    site = args[1];
} else if (args.length) {
    console.error("usage: node crates/carom-web/test/download-size.mjs [--site DIR]");
    process.exit(2);
}

const size = (bytes) => (bytes >= 1e6 ? `${(bytes / 1e6).toFixed(2)} MB` : `${(bytes / 1e3).toFixed(1)} kB`);
const files = fs.readdirSync(site).filter((name) => fs.statSync(path.join(site, name)).isFile()).sort();
if (!files.some((name) => name.endsWith(".wasm"))) {
    console.error(`${site} holds no .wasm file: build the site first (crates/carom-web/build-site.sh)`);
    process.exit(1);
}
console.log("file,size,gzipped");
let total = 0, totalGzipped = 0;
for (const name of files) {
    const bytes = fs.readFileSync(path.join(site, name));
    const gzipped = zlib.gzipSync(bytes, { level: 9 }).length;
    total += bytes.length;
    totalGzipped += gzipped;
    console.log([`\`${name}\``, size(bytes.length), size(gzipped)].join(","));
}
console.log(["all", size(total), size(totalGzipped)].join(","));
