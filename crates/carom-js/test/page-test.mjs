// The package in a real browser: Debian's Chromium, headless, opens a small page that imports
// the package as a user's page would (test/page/index.html), builds and steps a world, draws
// it, runs a scene of demos/ and makes a mistake on purpose. Checks that it draws, that the
// scene ends in the native hash (CAROM_SCENE_HASHES, as for the Node suite), that the mistake
// is an Error with its message, and that the page logs no error.
//
//   node crates/carom-js/test/page-test.mjs [--package target/carom-js/package]
//       [--hashes FILE] [--chromium /usr/bin/chromium]
//
// playwright-core comes from the web build's test folder (`npm ci --prefix crates/carom-web/test`).
import { createRequire } from "node:module";
import fs from "node:fs";
import http from "node:http";
import path from "node:path";

const require = createRequire(new URL("../../carom-web/test/package.json", import.meta.url));
const { chromium } = require("playwright-core");

const options = { package: process.env.CAROM_JS ?? "target/carom-js/package",
    hashes: process.env.CAROM_SCENE_HASHES, chromium: process.env.CHROMIUM ?? "/usr/bin/chromium" };
for (let i = 2; i < process.argv.length; i += 2) {
    const name = process.argv[i].replace(/^--/, "");
    if (!(name in options)) {
        console.error(`unknown option ${process.argv[i]}; options: ${Object.keys(options).join(", ")}`);
        process.exit(2);
    }
    options[name] = process.argv[i + 1];
}
const fail = (message) => {
    console.error(`FAIL ${message}`);
    process.exit(1);
};
const check = (ok, message) => ok ? console.log(`ok   ${message}`) : fail(message);

// /carom-js/ is the package, /demos/ the scenes, the rest the page.
const roots = { "carom-js": path.resolve(options.package), demos: path.resolve("demos") };
const page_root = path.resolve(path.dirname(new URL(import.meta.url).pathname), "page");
const types = { ".html": "text/html", ".js": "text/javascript", ".wasm": "application/wasm" };
const server = http.createServer((request, response) => {
    const [, first, ...rest] = decodeURIComponent(new URL(request.url, "http://x").pathname).split("/");
    const root = roots[first] ?? page_root;
    const file = path.resolve(root, roots[first] ? rest.join("/") : [first, ...rest].join("/") || "index.html");
    fs.readFile(file, (error, data) => {
        if (error || !file.startsWith(root + path.sep)) {
            response.writeHead(404);
            response.end();
            return;
        }
        response.writeHead(200, { "content-type": types[path.extname(file)] ?? "application/octet-stream" });
        response.end(data);
    });
});
await new Promise((resolve) => server.listen(0, "127.0.0.1", resolve));

const browser = await chromium.launch({
    executablePath: options.chromium,
    args: ["--no-sandbox", "--no-first-run", "--disable-background-networking", "--disable-component-update"],
});
const errors = [];
try {
    const page = await browser.newPage();
    page.on("pageerror", (e) => errors.push(String(e)));
    page.on("console", (m) => m.type() === "error" && errors.push(m.text()));
    // The scene is stepped as far as the native hashes were (40 steps without them).
    const native = options.hashes && fs.readFileSync(options.hashes, "utf8").split("\n")
        .map((line) => line.split(" ")).find(([name]) => name === "pyramid");
    const steps = native ? native[2] : "40";
    await page.goto(`http://127.0.0.1:${server.address().port}/index.html?scene=pyramid&steps=${steps}`);
    await page.waitForFunction(() => window.result !== undefined, null, { timeout: 60_000 });
    const result = await page.evaluate(() => window.result);
    check(!result.failure, `the page ran${result.failure ? `: ${result.failure}` : ""}`);
    const manifest = JSON.parse(fs.readFileSync(path.join(roots["carom-js"], "package.json"), "utf8"));
    check(result.version === manifest.version, `the page imported carom-js ${result.version}`);
    check(result.boxes === 36 && Math.abs(result.top.y - 7.5) < 0.1,
        `its pyramid of ${result.boxes} boxes stands (top at y = ${result.top.y.toFixed(3)})`);
    const drawn = await page.evaluate(() => {
        const { data } = document.getElementById("view").getContext("2d").getImageData(0, 0, 640, 400);
        let lit = 0;
        for (let i = 0; i < data.length; i += 4) lit += data[i] > 200 && data[i + 1] > 130 ? 1 : 0;
        return lit;
    });
    check(drawn > 36 * 300, `it drew the boxes (${drawn} pixels)`);
    check(/^Error: this body was removed from its world$/.test(result.staleError),
        `a stale handle is an Error with its message (${result.staleError})`);
    check(result.stepsAfterError === 121 && result.liveWorlds === 0,
        "the world steps after the mistake, and both worlds were freed");
    if (options.hashes) {
        check(result.scene.hash === native?.[1],
            `${result.scene.name} after ${result.scene.steps} steps: ${result.scene.hash} in the page, ${native?.[1]} natively`);
    }
    check(errors.length === 0, `the page logged no error${errors.length ? `: ${errors.join("; ")}` : ""}`);
} finally {
    await browser.close();
    server.close();
}
