// The time from a query to its answer in `archstudy explore` under concurrent load on
// loopback: a continuum state, a 64-voussoir state and a regime map, each asked by CLIENTS
// clients at once, at the 50th and 99th percentile. A recorded figure, not a test: every
// answer is only checked to be a 200 with the expected key. Prints a Markdown table.
//
// Usage: node explore-load.mjs ARCHSTUDY [CLIENTS] [REQUESTS_PER_CLIENT]
import { spawn } from "node:child_process";
import { availableParallelism } from "node:os";

const [bin, clientsArg, perArg] = process.argv.slice(2);
if (!bin) {
  console.error("usage: node explore-load.mjs ARCHSTUDY [CLIENTS] [REQUESTS_PER_CLIENT]");
  process.exit(2);
}
const clients = +(clientsArg || 8);
const perClient = +(perArg || 40);

const server = spawn(bin, ["explore", "--port", "0"], { stdio: ["ignore", "pipe", "inherit"] });
const url = await new Promise((resolve, reject) => {
  let out = "";
  server.stdout.on("data", (d) => {
    out += d;
    const m = out.match(/serving (http:\/\/\S+)/);
    if (m) resolve(m[1]);
  });
  server.on("exit", (code) => reject(new Error(`archstudy explore exited with ${code}`)));
});

const kinds = [
  ["continuum state", "api/scene?mu=0.35&k=", "state", perClient],
  ["64-voussoir state", "api/scene?mu=0.35&voussoirs=64&k=", "state", perClient],
  ["regime map (31 × 31, located)", "api/map?mu=0.35&k=", "bifurcations", Math.max(2, Math.floor(perClient / 8))],
];
const pct = (s, p) => s[Math.min(s.length - 1, Math.round((p / 100) * (s.length - 1)))];

console.log(`${clients} concurrent clients on loopback, ${availableParallelism()} cores`);
console.log("| query | requests | p50 (ms) | p99 (ms) | max (ms) |");
console.log("|---|---|---|---|---|");
try {
  for (const [name, path, key, n] of kinds) {
    const times = [];
    await Promise.all(Array.from({ length: clients }, async (_, c) => {
      for (let i = 0; i < n; i++) {
        // A different K each time: no answer is a repeat.
        const k = (1.10 + 0.3 * (c * n + i) / (clients * n)).toFixed(6);
        const t = performance.now();
        const r = await fetch(`${url}${path}${k}`);
        const body = await r.json();
        times.push(performance.now() - t);
        if (r.status !== 200 || !(key in body)) throw new Error(`${name}: ${r.status} ${JSON.stringify(body).slice(0, 200)}`);
      }
    }));
    times.sort((a, b) => a - b);
    console.log(`| ${name} | ${times.length} | ${pct(times, 50).toFixed(1)} | ${pct(times, 99).toFixed(1)} | ${times[times.length - 1].toFixed(1)} |`);
  }
} finally {
  server.kill();
}
