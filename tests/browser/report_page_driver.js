// Opens a result folder's report.html in headless Chromium and reports what a user would see,
// for tests/browser/report_browser_test.cpp to judge (the assertions live there, in C++).
//
//   node report_page_driver.js CHROMIUM FOLDER OUT_DIR [CLICK_A CLICK_B ...]
//
// Chromium is driven over its DevTools protocol on a pipe (--remote-debugging-pipe: JSON
// messages ending in NUL on file descriptors 3 and 4), so the test needs Node alone: no npm
// package, no network. Prints one JSON object on stdout:
//   console: [{level, text}]        console messages, uncaught exceptions, browser log entries
//   requests: [url]                 every request the page made
//   dom: {...}                      maps, pairs and decisions as the page lists them
//   component_views: [{id, view, rect, screenshot}]  per merged map's viewer as loaded: its
//                                   preview pixel -> device-pixel matrix (view), its canvas's box
//                                   and a screenshot of it (device pixels, file in OUT_DIR)
//   clicks: [{a, b, state, pair, hypothesis, view, rect, screenshot}]  per clicked table row:
//                                   the overlay viewer's state after the click, its world ->
//                                   device-pixel matrix (view), its canvas's box in CSS pixels
//                                   of the page (rect) and a
//                                   screenshot of it (device pixels, file in OUT_DIR)
//   second: the same for the last clicked pair's second hypothesis (its button clicked)
//   sorted: {initial, omega_first_click, omega_second_click}: the rows ("a|b") in table order
//   page_screenshot, pairs_screenshot: files in OUT_DIR (the top of the page; the pair table
//                                   with the last click's overlay)
//   timing_ms: {load, total}
// Exits 2 when Chromium cannot be started or the page never becomes ready.
"use strict";
const { spawn } = require("child_process");
const fs = require("fs");
const path = require("path");
const os = require("os");

const [chromium, folder, outDir, ...clickArgs] = process.argv.slice(2);
if (!chromium || !folder || !outDir || clickArgs.length % 2) {
  console.error("usage: node report_page_driver.js CHROMIUM FOLDER OUT_DIR [A B ...]");
  process.exit(64);
}
const DEVICE_SCALE = 2;  // overlays read back at 2 device pixels per CSS pixel
const VIEWPORT = { width: 1280, height: 900 };
const started = Date.now();
const profile = fs.mkdtempSync(path.join(os.tmpdir(), "fleetmerge-chromium-"));

const browser = spawn(chromium, [
  "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
  "--disable-background-networking", "--disable-component-update", "--disable-sync",
  "--disable-extensions", "--force-color-profile=srgb", "--hide-scrollbars",
  "--disable-dev-shm-usage",  // containers' small /dev/shm crashes Chromium's renderer
  "--remote-debugging-pipe", "--user-data-dir=" + profile, "about:blank",
], { stdio: ["ignore", "ignore", "pipe", "pipe", "pipe"] });
let stderr = "";
browser.stderr.on("data", (d) => { stderr += d; });

function fail(message) {
  process.stderr.write("report_page_driver: " + message + "\n" + stderr.slice(-2000) + "\n");
  finish(2);
}
// Closes Chromium (politely, then SIGKILL after 3 s), removes its profile once it has exited
// (it writes there until then), and exits with `code`.
let finishing = false;
function finish(code) {
  if (finishing) return;
  finishing = true; finished = true;
  const done = () => {
    try { fs.rmSync(profile, { recursive: true, force: true }); } catch (e) { /* best effort */ }
    process.exit(code);
  };
  if (browser.exitCode !== null || browser.signalCode !== null) return done();
  browser.on("exit", done);
  const kill = setTimeout(() => { try { browser.kill("SIGKILL"); } catch (e) { /* gone */ } }, 3000);
  kill.unref();
  session = undefined;
  try { send("Browser.close").catch(() => {}); } catch (e) { browser.kill("SIGKILL"); }
}
const deadline = setTimeout(() => fail("timed out after 90 s"), 90000);
browser.on("error", (e) => fail("cannot start " + chromium + ": " + e.message));
browser.on("exit", (code) => { if (!finished) fail("chromium exited early (" + code + ")"); });
let finished = false;

// ---- The protocol: commands with ids, replies matched by id, events to listeners.
const toBrowser = browser.stdio[3], fromBrowser = browser.stdio[4];
let nextId = 1, buffer = "";
const pending = new Map(), listeners = [];
fromBrowser.on("data", (chunk) => {
  buffer += chunk.toString("utf8");
  let end;
  while ((end = buffer.indexOf("\0")) >= 0) {
    const message = JSON.parse(buffer.slice(0, end));
    buffer = buffer.slice(end + 1);
    if (message.id && pending.has(message.id)) {
      const { resolve, reject, method } = pending.get(message.id);
      pending.delete(message.id);
      if (message.error) reject(new Error(method + ": " + message.error.message));
      else resolve(message.result);
    } else if (message.method) {
      for (const l of listeners) l(message);
    }
  }
});
let session = undefined;
function send(method, params) {
  const id = nextId++;
  toBrowser.write(JSON.stringify({ id, method, params: params || {}, sessionId: session }) + "\0");
  return new Promise((resolve, reject) => pending.set(id, { resolve, reject, method }));
}
function waitForEvent(method, timeoutMs) {
  return new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error("no " + method)), timeoutMs);
    listeners.push(function once(m) {
      if (m.method !== method) return;
      clearTimeout(timer);
      listeners.splice(listeners.indexOf(once), 1);
      resolve(m.params);
    });
  });
}
async function evaluate(expression) {
  const r = await send("Runtime.evaluate", { expression, awaitPromise: true, returnByValue: true });
  if (r.exceptionDetails) throw new Error("page: " + JSON.stringify(r.exceptionDetails));
  return r.result.value;
}
// Polls `expression` until it is truthy.
async function waitFor(expression, what, timeoutMs) {
  const until = Date.now() + (timeoutMs || 20000);
  for (;;) {
    const value = await evaluate(expression);
    if (value) return value;
    if (Date.now() > until) throw new Error("timed out waiting for " + what);
    await new Promise((r) => setTimeout(r, 50));
  }
}
async function screenshot(file, clip) {
  const params = { format: "png", captureBeyondViewport: false };
  if (clip) params.clip = { ...clip, scale: 1 };
  const shot = await send("Page.captureScreenshot", params);
  fs.writeFileSync(path.join(outDir, file), Buffer.from(shot.data, "base64"));
  return file;
}
// A real click: mouse pressed and released at the element's centre.
async function click(selector) {
  const box = await evaluate(`(() => { const e = document.querySelector(${JSON.stringify(selector)});
    if (!e) return null; e.scrollIntoView({block: "center"}); const r = e.getBoundingClientRect();
    return {x: r.x + r.width / 2, y: r.y + r.height / 2}; })()`);
  if (!box) throw new Error("nothing to click: " + selector);
  for (const type of ["mousePressed", "mouseReleased"]) {
    await send("Input.dispatchMouseEvent", { type, x: box.x, y: box.y, button: "left",
      clickCount: 1 });
  }
}

const consoleMessages = [], requests = [];
listeners.push((m) => {
  if (m.method === "Runtime.consoleAPICalled") {
    consoleMessages.push({ level: m.params.type,
      text: m.params.args.map((a) => a.value ?? a.description ?? "").join(" ") });
  } else if (m.method === "Runtime.exceptionThrown") {
    const d = m.params.exceptionDetails;
    consoleMessages.push({ level: "error", text: "uncaught: " +
      ((d.exception && d.exception.description) || d.text) });
  } else if (m.method === "Log.entryAdded") {
    consoleMessages.push({ level: m.params.entry.level, text: m.params.entry.text +
      (m.params.entry.url ? " (" + m.params.entry.url + ")" : "") });
  } else if (m.method === "Network.requestWillBeSent") {
    requests.push(m.params.request.url);
  }
});

(async () => {
  const targets = await send("Target.getTargets");
  const target = targets.targetInfos.find((t) => t.type === "page");
  if (!target) throw new Error("no page target");
  const attached = await send("Target.attachToTarget", { targetId: target.targetId, flatten: true });
  session = attached.sessionId;
  for (const domain of ["Page", "Runtime", "Log", "Network"]) await send(domain + ".enable");
  await send("Emulation.setDeviceMetricsOverride", { ...VIEWPORT, deviceScaleFactor: DEVICE_SCALE,
    mobile: false });
  const url = "file://" + path.resolve(folder, "report.html");
  const loaded = waitForEvent("Page.loadEventFired", 20000);
  const loadStart = Date.now();
  await send("Page.navigate", { url });
  await loaded;
  await waitFor("document.body && document.body.dataset.ready === 'true'", "the page's script");
  // The first merged map is in view at the top: it loads lazily on its own.
  await waitFor("[...document.querySelectorAll('.component')].every(c => c.dataset.loaded) ",
    "the merged maps");
  const loadMs = Date.now() - loadStart;
  await new Promise((r) => setTimeout(r, 100));
  const pageShot = await screenshot("page.png");

  // Each merged map's viewer as drawn at load (fitted, pose graph on): its preview pixel ->
  // device-pixel matrix and a screenshot of its canvas.
  const componentViews = [];
  for (const id of await evaluate(
    "[...document.querySelectorAll('.component')].map(c => c.dataset.component)")) {
    const selector = `.component[data-component="${id}"] .viewer`;
    await evaluate(`document.querySelector(${JSON.stringify(selector)})
      .scrollIntoView({block: "center"})`);
    await new Promise((r) => setTimeout(r, 50));
    const info = await evaluate(`(() => {
      const v = document.querySelector(${JSON.stringify(selector)});
      const r = v.querySelector('canvas').getBoundingClientRect();
      return { id: ${JSON.stringify(id)}, view: JSON.parse(v.dataset.view || "null"),
        rect: {x: r.x + window.scrollX, y: r.y + window.scrollY, width: r.width, height: r.height}
      }; })()`);
    info.screenshot = await screenshot("component_" + id + ".png", info.rect);
    componentViews.push(info);
  }

  // Lazily drawn overlays of unmerged maps: scroll each into view.
  await evaluate(`(async () => {
    for (const v of document.querySelectorAll('[data-role=best-candidate]')) {
      v.scrollIntoView({block: "center"});
      await new Promise(r => setTimeout(r, 30));
    } })()`);
  await waitFor("[...document.querySelectorAll('[data-role=best-candidate]')].every(" +
    "v => v.dataset.state === 'drawn')", "the unmerged maps' best candidates");

  // Octree jobs: the floor plans, lazily drawn too.
  await evaluate(`(async () => {
    for (const c of document.querySelectorAll('[data-octree]')) {
      c.scrollIntoView({block: "center"});
      await new Promise(r => setTimeout(r, 30));
    } })()`);
  await waitFor("[...document.querySelectorAll('[data-octree]')].every(c => c.dataset.loaded)",
    "the octrees' floor plans");

  const dom = await evaluate(`(() => {
    const text = (e) => e ? e.textContent.trim() : null;
    return {
      title: document.title,
      input_maps: [...document.querySelectorAll('#input-table tr[data-map]')].map(r => r.dataset.map),
      input_rows: [...document.querySelectorAll('#input-table tr[data-map]')].map(r =>
        [...r.cells].map(c => c.textContent.trim())),
      pairs: [...document.querySelectorAll('#pair-table tbody tr')].map(r => ({
        a: r.dataset.a, b: r.dataset.b, decision: r.dataset.decision,
        cells: [...r.cells].map(c => c.textContent.trim())})),
      components: [...document.querySelectorAll('.component')].map(c => ({
        id: c.dataset.component,
        legend: [...c.querySelectorAll('.legend li[data-map]')].map(l => l.dataset.map),
        legend_text: [...c.querySelectorAll('.legend li[data-map]')].map(l => l.textContent),
        canvas: [c.querySelector('canvas').width, c.querySelector('canvas').height]})),
      unmerged: [...document.querySelectorAll('#unmerged-list .card')].map(c => ({
        map: c.dataset.map,
        best: c.querySelector('[data-role=best-candidate]') ?
          c.querySelector('[data-role=best-candidate]').dataset.pair : null})),
      octrees: [...document.querySelectorAll('[data-octree]')].map(c => c.dataset.octree),
      octree_text: text(document.getElementById('octrees')),
      summary: text(document.getElementById('summary')),
      options: text(document.getElementById('options')),
      timing: text(document.getElementById('timing-table')),
    }; })()`);

  const clicks = [];
  for (let k = 0; k < clickArgs.length; k += 2) {
    const [a, b] = [clickArgs[k], clickArgs[k + 1]];
    await click(`#pair-table tr[data-a="${a}"][data-b="${b}"]`);
    const state = await waitFor(`(() => { const v = document.getElementById('overlay-viewer');
      return v.dataset.state === 'drawn' && v.dataset.pair === ${JSON.stringify(a + "|" + b)}
        ? v.dataset.state : null; })()`, "the overlay of " + a + " and " + b);
    await evaluate("document.getElementById('overlay-viewer').scrollIntoView({block: 'center'})");
    await new Promise((r) => setTimeout(r, 50));
    const info = await evaluate(`(() => { const v = document.getElementById('overlay-viewer');
      const r = v.querySelector('canvas').getBoundingClientRect();
      return { pair: v.dataset.pair, hypothesis: Number(v.dataset.hypothesis),
        view: JSON.parse(v.dataset.view),
        rect: {x: r.x + window.scrollX, y: r.y + window.scrollY, width: r.width, height: r.height},
        title: document.getElementById('overlay-title').textContent,
        numbers: document.getElementById('overlay-numbers').textContent,
        hypotheses: [...document.querySelectorAll('#overlay-hyps button')].map(b => b.textContent)
      }; })()`);
    const file = "overlay_" + a + "_" + b + ".png";
    await screenshot(file, info.rect);
    clicks.push({ a, b, state, ...info, screenshot: file });
  }
  // The last clicked pair's second hypothesis, from its button.
  let second = null;
  if (clicks.length && clicks[clicks.length - 1].hypotheses.length > 1) {
    const last = clicks[clicks.length - 1];
    await click('#overlay-hyps button[data-hypothesis="1"]');
    await waitFor(`(() => { const v = document.getElementById('overlay-viewer');
      return v.dataset.state === 'drawn' && v.dataset.hypothesis === '1'; })()`,
      "the second hypothesis");
    await evaluate("document.getElementById('overlay-viewer').scrollIntoView({block: 'center'})");
    await new Promise((r) => setTimeout(r, 50));
    second = await evaluate(`(() => { const v = document.getElementById('overlay-viewer');
      const r = v.querySelector('canvas').getBoundingClientRect();
      return { pair: v.dataset.pair, hypothesis: Number(v.dataset.hypothesis), state: v.dataset.state,
        view: JSON.parse(v.dataset.view),
        rect: {x: r.x + window.scrollX, y: r.y + window.scrollY, width: r.width, height: r.height},
        hypotheses: [...document.querySelectorAll('#overlay-hyps button')].map(b => b.textContent)
      }; })()`);
    second.screenshot = await screenshot("overlay_" + last.a + "_" + last.b + "_h2.png", second.rect);
    // Back to the first, so that the page is left showing the best hypothesis.
    await click('#overlay-hyps button[data-hypothesis="0"]');
    await waitFor(`document.getElementById('overlay-viewer').dataset.hypothesis === '0'`,
      "the first hypothesis again");
  }
  // Sorting: the order of the rows after one and two clicks on the omega heading.
  const order = () => evaluate(`[...document.querySelectorAll('#pair-table tbody tr')].map(
    r => r.dataset.a + '|' + r.dataset.b)`);
  const sorted = { initial: await order() };
  await click('#pair-table th[data-key="omega"]');
  sorted.omega_first_click = await order();
  await click('#pair-table th[data-key="omega"]');
  sorted.omega_second_click = await order();

  const pairsShot = await (async () => {
    await evaluate("document.getElementById('pairs').scrollIntoView()");
    await new Promise((r) => setTimeout(r, 100));
    return screenshot("pairs.png");
  })();

  finished = true;
  clearTimeout(deadline);
  process.stdout.write(JSON.stringify({ console: consoleMessages, requests, dom,
    component_views: componentViews, clicks, second, sorted,
    page_screenshot: pageShot, pairs_screenshot: pairsShot, device_scale: DEVICE_SCALE,
    timing_ms: { load: loadMs, total: Date.now() - started } }) + "\n");
  finish(0);
})().catch((e) => fail(e.stack || String(e)));
