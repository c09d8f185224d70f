// The gallery page (gallery/index.html) in headless Chromium (Debian's /usr/bin/chromium, driven
// by playwright-core as the lab's test is), opened from file:// as a reader opens it offline.
// At 1280 px and at a phone's 390 px, in the light and the dark colour scheme, it checks
//   - no sideways scroll (the page is no wider than the window);
//   - every image loads (SVG figures and GIFs, thumbnails included);
//   - every contents entry points to a section that exists, each section once;
//   - every "Open in the lab" link carries the lab's share-link fields (system, method, dt,
//     params as JSON);
//   - no console errors;
// and saves a screenshot of each to the given directory. With --open-links, it then serves the
// lab built into the gallery (GALLERY_DIR/lab, as scripts/demo builds it) and opens every
// link's fragment in it: the lab must refuse nothing and open the linked system.
//
//   node web/test/gallery.mjs GALLERY_DIR SCREENSHOT_DIR [--open-links]
import { join, resolve } from "node:path";
import { pathToFileURL } from "node:url";
import { existsSync, mkdirSync } from "node:fs";
import { launch, serve } from "./harness.mjs";

const openLinks = process.argv.includes("--open-links");
const [gallery, shots] = process.argv.slice(2).filter((a) => !a.startsWith("--"));
if (!gallery || !shots) {
  console.error("usage: node web/test/gallery.mjs GALLERY_DIR SCREENSHOT_DIR [--open-links]");
  process.exit(2);
}
mkdirSync(shots, { recursive: true });
const url = pathToFileURL(join(resolve(gallery), "index.html")).href;
const browser = await launch();
const failures = [];
const labLinks = new Set();
const fail = (what) => { failures.push(what); console.log(`FAIL ${what}`); };

for (const [name, width, scheme] of [["desktop", 1280, "light"], ["phone", 390, "light"], ["desktop-dark", 1280, "dark"], ["phone-dark", 390, "dark"]]) {
  const page = await browser.newPage({ viewport: { width, height: 900 }, colorScheme: scheme });
  const errors = [];
  page.on("console", (m) => { if (m.type() === "error") errors.push(m.text()); });
  page.on("pageerror", (e) => errors.push(String(e)));
  await page.goto(url);
  // Lazy images: scroll through the page so every one is fetched, then wait for them.
  await page.evaluate(async () => {
    for (const img of document.images) img.loading = "eager";
    await Promise.all([...document.images].map((img) => img.complete ? null : new Promise((ok) => { img.onload = ok; img.onerror = ok; })));
  });
  const facts = await page.evaluate(() => ({
    scroll: document.scrollingElement.scrollWidth,
    inner: window.innerWidth,
    broken: [...document.images].filter((i) => !(i.complete && i.naturalWidth > 0)).map((i) => i.getAttribute("src")),
    contents: [...document.querySelectorAll("nav.contents a")].map((a) => a.getAttribute("href")),
    ids: [...document.querySelectorAll("section[id]")].map((s) => s.id),
    lab: [...document.querySelectorAll("a.lab")].map((a) => a.getAttribute("href")),
  }));
  if (facts.scroll > facts.inner) fail(`${name}: page ${facts.scroll} px wide in a ${facts.inner} px window`);
  for (const src of facts.broken) fail(`${name}: image ${src} does not load`);
  if (new Set(facts.ids).size !== facts.ids.length) fail(`${name}: duplicate section ids`);
  if (facts.contents.length !== facts.ids.length) fail(`${name}: ${facts.contents.length} contents entries for ${facts.ids.length} sections`);
  for (const href of facts.contents) {
    if (!facts.ids.includes(href.replace(/^#/, ""))) fail(`${name}: contents link ${href} has no section`);
  }
  for (const href of facts.lab.filter((h) => h.includes("#"))) {
    const h = new URLSearchParams(href.split("#")[1]);
    for (const key of ["system", "method", "dt", "params"]) if (!h.get(key)) fail(`${name}: lab link without ${key}: ${href}`);
    try { JSON.parse(h.get("params")); } catch { fail(`${name}: lab link params are no JSON: ${href}`); }
    if (!Number.isFinite(Number(h.get("dt")))) fail(`${name}: lab link dt is no number: ${href}`);
    labLinks.add(href);
  }
  for (const e of errors) fail(`${name}: console: ${e}`);
  await page.screenshot({ path: join(shots, `gallery-${name}.png`) });
  await page.screenshot({ path: join(shots, `gallery-${name}-full.png`), fullPage: true });
  await page.close();
}
// The lab itself opens every link: nothing refused, the linked system shown.
const labDir = join(resolve(gallery), "lab");
let opened = 0;
if (openLinks && existsSync(join(labDir, "index.html"))) {
  const { server, url: labUrl } = await serve(labDir);
  const page = await browser.newPage({ viewport: { width: 1280, height: 900 } });
  const errors = [];
  page.on("pageerror", (e) => errors.push(String(e)));
  await page.goto(labUrl);
  await page.evaluate(() => window.physicskitLab.ready);
  for (const href of labLinks) {
    const hash = `#${href.split("#")[1]}`;
    const system = new URLSearchParams(hash.slice(1)).get("system");
    const got = await page.evaluate((h) => {
      const lab = window.physicskitLab;
      const ok = lab.openHash(h);
      return { ok, system: lab.app.entry.name, message: document.getElementById("message").textContent };
    }, hash);
    if (!got.ok) fail(`lab refused part of ${href}: ${got.message}`);
    if (got.system !== system) fail(`lab opened ${got.system} for ${href}`);
    opened += 1;
  }
  for (const e of errors) fail(`lab: ${e}`);
  await page.close();
  server.close();
} else if (openLinks) {
  fail(`no lab at ${labDir} to open the links in`);
}
await browser.close();
if (failures.length) {
  console.log(`gallery page: ${failures.length} failure(s)`);
  process.exit(1);
}
console.log(`gallery page: desktop and 390 px, light and dark: no sideways scroll, every image loads, contents and lab links sound${openLinks ? `; ${opened} of ${labLinks.size} lab links opened in the lab` : ""}`);
