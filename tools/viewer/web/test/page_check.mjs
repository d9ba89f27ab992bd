// Opens the viewer's page in headless Chromium (Debian's, driven by playwright-core), waits until
// the page has drawn the scene from the WebSocket (services alive, a committed trajectory, map
// voxels, the flown path, decisions), checks the DOM (timeline marks, health rows, a decision's
// details after a click) and takes a screenshot.
//   node page_check.mjs http://127.0.0.1:8765/ OUT.png MIN_SERVICES TIMEOUT_S
import { existsSync } from "node:fs";
import { chromium } from "playwright-core";

const [url, screenshot, minServicesText = "5", timeoutText = "30"] = process.argv.slice(2);
const minServices = Number(minServicesText);
const executablePath = ["/usr/lib/chromium/chromium", "/usr/bin/chromium"].find((p) => existsSync(p));
const browser = await chromium.launch({
  executablePath,
  args: ["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--ignore-gpu-blocklist"],
});
const errors = [];
let code = 1;
try {
  const page = await browser.newPage({ viewport: { width: 1440, height: 860 } });
  page.on("pageerror", (e) => errors.push(String(e)));
  page.on("console", (m) => m.type() === "error" && errors.push(m.text()));
  await page.goto(url);
  await page.waitForFunction(
    (n) => {
      const d = document.body.dataset;
      return d.connection === "connected" && +d.servicesAlive >= n && +d.trajectories >= 1 &&
        +d.decisions >= 1 && +d.voxels >= 100 && +d.pathPoints >= 10 && +d.odometry >= 1;
    },
    minServices,
    { timeout: Number(timeoutText) * 1000, polling: 250 },
  );
  const rows = await page.locator("#health-rows tr[data-alive=true]").count();
  if (rows < minServices) throw new Error(`${rows} live health rows, expected ${minServices}`);
  // The rest of the flight, for a screenshot of the whole mission.
  await page.waitForFunction(() => document.body.dataset.mission === "goal reached", null, {
    timeout: Number(timeoutText) * 1000,
  });
  await page.locator("#timeline .mark").last().click();
  const details = await page.locator("#decision").innerText();
  if (!/Decision #\d+/.test(details) || !/trigger/.test(details)) throw new Error(`no decision details: ${details}`);
  await page.waitForTimeout(500); // let the last messages render
  await page.screenshot({ path: screenshot });
  const state = await page.evaluate(() => ({ ...document.body.dataset }));
  const marks = await page.locator("#timeline .mark").count();
  if (marks !== Number(state.decisions)) throw new Error(`${marks} timeline marks for ${state.decisions} decisions`);
  if (errors.length) throw new Error(`page errors: ${errors.join("; ")}`);
  console.log(`ok: page ${JSON.stringify(state)}, ${marks} timeline marks, ${rows} live services`);
  code = 0;
} catch (e) {
  console.log(`FAIL: ${e.message}`);
  if (errors.length) console.log(`page errors: ${errors.join("; ")}`);
} finally {
  await browser.close();
}
process.exit(code);
