// Drives `archstudy explore` in Debian's Chromium and fails on any broken promise of the
// page: a console error, a regime that does not change from stable to mixed within one
// control step of the solver's K_c at μ = 0.35, hinges or sliding joints that differ from
// `archstudy solve --json`'s, a URL that does not reopen its scene, a map click that does not
// move the scene there, a bad value that is not named, and (with a run directory) a click on
// the run's regime map that does not show the case clicked. Screenshots of every view go to
// the directory given.
//
// Usage: node explore-check.mjs ARCHSTUDY RUN_DIR SHOT_DIR
import { spawn, execFileSync } from "node:child_process";
import { mkdirSync } from "node:fs";
import { chromium } from "playwright-core";

const [bin, runDir, shots] = process.argv.slice(2);
if (!bin || !runDir || !shots) {
  console.error("usage: node explore-check.mjs ARCHSTUDY RUN_DIR SHOT_DIR");
  process.exit(2);
}
mkdirSync(shots, { recursive: true });

const failures = [];
const check = (ok, what) => {
  console.log(`${ok ? "ok  " : "FAIL"} ${what}`);
  if (!ok) failures.push(what);
};

function serve(args) {
  return new Promise((resolve, reject) => {
    const child = spawn(bin, ["explore", "--port", "0", ...args], { stdio: ["ignore", "pipe", "inherit"] });
    let out = "";
    child.stdout.on("data", (d) => {
      out += d;
      const m = out.match(/serving (http:\/\/\S+)/);
      if (m) resolve({ child, url: m[1] });
    });
    child.on("exit", (code) => reject(new Error(`archstudy explore exited with ${code}`)));
    setTimeout(() => reject(new Error("archstudy explore printed no address")), 30000);
  });
}

const solve = (...args) => JSON.parse(execFileSync(bin, ["solve", "--json", ...args]).toString());

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
  args: ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync"],
});
const context = await browser.newContext({ viewport: { width: 1500, height: 1100 } });
const consoleErrors = [];
function watch(p) {
  // A 400 is how the server answers a bad value (the page shows it in its error box); any
  // other message is a fault.
  p.on("console", (m) => {
    if ((m.type() === "error" || m.type() === "warning") && !/status of 400/.test(m.text())) consoleErrors.push(m.text());
  });
  p.on("pageerror", (e) => consoleErrors.push(String(e)));
  return p;
}

// The page pixel of (μ, K) on the map in `selector`, through the plotting frame the page
// holds (`ui[key]`, or its first panel).
function pixelOf(p, selector, key, target) {
  return p.evaluate(({ selector, key, mu, k }) => {
    const f = Array.isArray(ui[key]) ? ui[key][0] : ui[key];
    const svg = document.querySelector(`${selector} svg`);
    const r = svg.getBoundingClientRect();
    const s = r.width / svg.viewBox.baseVal.width;
    return {
      x: r.left + s * (f.left + (mu - f.x[0]) / (f.x[1] - f.x[0]) * (f.right - f.left)),
      y: r.top + s * (f.bottom - (k - f.y[0]) / (f.y[1] - f.y[0]) * (f.bottom - f.top)),
    };
  }, { selector, key, ...target });
}

const regimeOf = (p) => p.locator("#regime").getAttribute("data-regime");
async function settled(p) {
  // No request in flight or pending, and the figure of the last answer placed.
  await p.waitForFunction(() => typeof ui !== "undefined" && !ui.inflight && !ui.pending && ui.lastScene !== null, null, { timeout: 30000 });
}
async function joints(p) {
  return p.$$eval("#joints-table tbody tr", (rows) => rows.map((r) => ({
    kind: r.dataset.kind, angle: +r.dataset.angle, side: r.dataset.face || r.dataset.sense,
  })));
}

const scene = await serve([]);
try {
  const p = watch(await context.newPage());
  await p.goto(`${scene.url}?k=1.3&mu=0.35`);
  await settled(p);
  check((await regimeOf(p)) === "stable", "K = 1.3, μ = 0.35 is shown stable");

  // K_c at μ = 0.35 from the solver; the K slider moves in steps of 0.001.
  const kc = solve("--find", "thickness", "--mu", "0.35").k_crit;
  const above = Math.ceil(kc * 1000) / 1000;
  await p.fill("#k-number", above.toFixed(3));
  await settled(p);
  check((await regimeOf(p)) === "stable", `K = ${above.toFixed(3)} (one step above K_c = ${kc}) is shown stable`);
  await p.focus("#k-range");
  await p.keyboard.press("ArrowLeft");
  await settled(p);
  const below = await p.inputValue("#k-number");
  check(+below < kc && +below > kc - 0.0011, `one step of the K slider goes to ${below}, below K_c`);
  check((await regimeOf(p)) === "mixed", `K = ${below} is shown mixed`);

  // The limit state drawn below K_c is solve's thickness find at μ = 0.35.
  const limit = solve("--find", "thickness", "--mu", "0.35");
  const drawn = await joints(p);
  const want = [
    ...limit.hinges.map((h) => ({ kind: "hinge", angle: h.angle_deg, side: h.face })),
    ...limit.sliding_joints.map((s) => ({ kind: "sliding", angle: s.angle_deg, side: s.sense })),
  ];
  const same = drawn.length === want.length && want.every((w, i) =>
    drawn[i].kind === w.kind && drawn[i].side === w.side && Math.abs(drawn[i].angle - w.angle) < 1e-9);
  check(same, `the ${want.length} hinges and sliding joints drawn equal solve --json's (${JSON.stringify(drawn)})`);
  const svgText = await p.locator("#state-fig svg").textContent();
  check(svgText.includes("Static limit") || svgText.includes("K_c") || svgText.includes("K = "), "the state figure names its limit state");

  await p.waitForSelector("#mechanism-fig svg", { timeout: 30000 });
  await p.waitForFunction(() => /points/.test(document.getElementById("map-info").textContent), null, { timeout: 60000 });
  await p.screenshot({ path: `${shots}/explore-scene.png`, fullPage: true });
  for (const id of ["state-view", "domains-view", "mechanism-view", "map-view"]) {
    await p.locator(`#${id}`).screenshot({ path: `${shots}/explore-${id}.png` });
  }
  const frames = await p.evaluate(() => ui.frames.length);
  check(frames >= 8, `the mechanism moves through ${frames} frames`);

  // The URL holds the scene.
  const url = p.url();
  const q = new URL(url).searchParams;
  check(q.get("k") === below && q.get("mu") === "0.35", `the URL holds the scene (${url})`);
  const p2 = watch(await context.newPage());
  await p2.goto(url);
  await settled(p2);
  check((await p2.inputValue("#k-number")) === below && (await regimeOf(p2)) === "mixed"
    && JSON.stringify(await joints(p2)) === JSON.stringify(drawn), "the URL reopens the same scene");
  await p2.close();

  // A click on the map moves the scene to the (μ, K) under the pointer.
  const target = { mu: 0.5, k: 1.25 };
  await p.locator("#map-fig").scrollIntoViewIfNeeded();
  const at = await pixelOf(p, "#map-fig", "mapFrame", target);
  await p.mouse.click(at.x, at.y);
  await settled(p);
  const [mu2, k2] = [+(await p.inputValue("#mu-number")), +(await p.inputValue("#k-number"))];
  check(Math.abs(mu2 - target.mu) < 0.01 && Math.abs(k2 - target.k) < 0.01,
    `a click on the map at (μ, K) = (0.5, 1.25) moves the scene to (${mu2}, ${k2})`);

  // A bad value is named.
  await p.fill("#k-number", "0.5");
  await settled(p);
  const err = await p.locator("#error").textContent();
  check(!(await p.locator("#error").isHidden()) && err.includes("'k'") && err.includes("0.5"), `a bad K is named: ${err}`);

  // Another form and a live load: a pointed arch under a point load, 12 voussoirs.
  await p.goto(`${scene.url}?k=1.3&mu=0.6&shape=pointed&eccentricity=0.2&voussoirs=12&load=point&at=-45&lambda=0.05`);
  await settled(p);
  await p.waitForFunction(() => /points|no map/.test(document.getElementById("map-info").textContent), null, { timeout: 120000 });
  await p.waitForFunction(() => ui.frames.length > 0 && document.querySelector("#mechanism-fig svg"), null, { timeout: 60000 });
  await p.screenshot({ path: `${shots}/explore-pointed-point-load.png`, fullPage: true });
  check(["stable", "rotational", "mixed", "sliding", "none"].includes(await regimeOf(p)), "a pointed arch under a point load is solved");
  await p.close();
} finally {
  scene.child.kill();
}

// A finished run: a click on its regime map shows the case clicked.
const run = await serve([runDir]);
try {
  const p = watch(await context.newPage());
  await p.goto(run.url);
  await p.waitForSelector("#run-fig svg", { timeout: 30000 });
  await settled(p);
  const target = { mu: 0.44, k: 1.23 };
  await p.locator("#run-fig").scrollIntoViewIfNeeded();
  const at = await pixelOf(p, "#run-fig", "runFrames", target);
  await p.mouse.click(at.x, at.y);
  await p.waitForFunction(() => document.getElementById("case-info").dataset.caseId !== undefined, null, { timeout: 30000 });
  await settled(p);
  const info = await p.locator("#case-info").evaluate((e) => ({ ...e.dataset, text: e.textContent }));
  check(Math.abs(+info.k - target.k) < 1e-9 && Math.abs(+info.mu - target.mu) < 1e-9,
    `a click at (μ, K) = (0.44, 1.23) on the run's map shows that case (${info.text})`);
  check(Math.abs(+(await p.inputValue("#k-number")) - target.k) < 1e-9
    && Math.abs(+(await p.inputValue("#mu-number")) - target.mu) < 1e-9,
    "the case's scene is loaded into the controls");
  await p.waitForSelector("#mechanism-fig svg", { timeout: 30000 }).catch(() => {});
  await p.screenshot({ path: `${shots}/explore-run.png`, fullPage: true });
  await p.locator("#run-view").screenshot({ path: `${shots}/explore-run-view.png` });
  await p.close();
} finally {
  run.child.kill();
}

await browser.close();
check(consoleErrors.length === 0, `no console message (${JSON.stringify(consoleErrors)})`);
if (failures.length) {
  console.error(`${failures.length} browser checks failed`);
  process.exit(1);
}
console.log("all browser checks passed");
