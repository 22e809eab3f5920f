// The package under test: the folder CAROM_JS names (an unpacked `npm pack` tarball in CI),
// else the folder build-package.sh writes.
import path from "node:path";
import { pathToFileURL } from "node:url";

export const packageDir = path.resolve(process.env.CAROM_JS ?? "target/carom-js/package");
export const carom = await import(pathToFileURL(path.join(packageDir, "index.js")).href);

/** A world with a static ground whose top is at y = 0, 40 m wide. */
export function withGround(settings) {
    const world = new carom.World(settings);
    const ground = world.createBody({
        type: "static",
        shape: { kind: "box", halfWidth: 20, halfHeight: 0.5 },
        position: { x: 0, y: -0.5 },
    });
    return { world, ground };
}

export const box = (half = 0.5) => ({ kind: "box", halfWidth: half, halfHeight: half });
