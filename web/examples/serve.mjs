// A tiny static server for the example page and the browser test:
//   node examples/serve.mjs [port]     (npm run serve; port 8080 by default, 0 for any)
// Serves the package folder (web/) at /, and the repository's assets/ at /assets/.
// Open http://localhost:8080/examples/pool/ after `npm install` and `npm run build`.
import { createServer } from "node:http";
import { readFile } from "node:fs/promises";
import { extname, normalize, sep } from "node:path";
import { fileURLToPath } from "node:url";

const web = fileURLToPath(new URL("..", import.meta.url));
const assets = fileURLToPath(new URL("../../assets/", import.meta.url));
const TYPES = {
  ".html": "text/html; charset=utf-8",
  ".js": "text/javascript; charset=utf-8",
  ".mjs": "text/javascript; charset=utf-8",
  ".json": "application/json",
  ".wasm": "application/wasm",
  ".obj": "text/plain; charset=utf-8",
  ".png": "image/png",
  ".css": "text/css; charset=utf-8",
};

export function serve(port = 8080) {
  const server = createServer(async (req, res) => {
    let path = decodeURIComponent(new URL(req.url, "http://x").pathname);
    if (path.endsWith("/")) path += "index.html";
    const [root, rest] = path.startsWith("/assets/") ? [assets, path.slice(8)] : [web, path.slice(1)];
    const file = normalize(root + rest);
    if (!file.startsWith(root) || file.includes(`${sep}..${sep}`)) {
      res.writeHead(403).end();
      return;
    }
    try {
      const body = await readFile(file);
      res.writeHead(200, { "content-type": TYPES[extname(file)] ?? "application/octet-stream" });
      res.end(body);
    } catch {
      res.writeHead(404, { "content-type": "text/plain" }).end(`not found: ${path}`);
    }
  });
  return new Promise((resolve) => server.listen(port, "127.0.0.1", () => resolve(server)));
}

if (process.argv[1] === fileURLToPath(import.meta.url)) {
  const server = await serve(Number(process.argv[2] ?? 8080));
  console.log(`http://localhost:${server.address().port}/examples/pool/`);
}
