// Opens the viewer's page in headless Chromium (Debian's, driven by playwright-core), waits until
// the page has drawn the scene from the WebSocket (services alive, a committed trajectory, map
// voxels, the flown path, decisions), checks the DOM (timeline marks, health rows, a decision's
// details after a click) and takes a screenshot.
// With EXPECT_DEBUG 1 (the planners publish PLAN_DEBUG) the debug layer must have objects.
//   node page_check.mjs http://127.0.0.1:8765/ OUT.png MIN_SERVICES TIMEOUT_S [EXPECT_DEBUG]
import { runPageCheck } from "./browser.mjs";

const [url, screenshot, minServicesText = "5", timeoutText = "30", expectDebug = "0"] = process.argv.slice(2);
const minServices = Number(minServicesText);
await runPageCheck(url, async (page) => {
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
  if (expectDebug === "1" && !(+state.debugPaths >= 1))
    throw new Error(`no debug layer drawn: ${JSON.stringify(state)}`);
  const marks = await page.locator("#timeline .mark").count();
  if (marks !== Number(state.decisions)) throw new Error(`${marks} timeline marks for ${state.decisions} decisions`);
  // Services that run report OK (or why not), never STARTING for the whole flight.
  const starting = await page.locator('#health-rows tr[data-state="STARTING"]').count();
  if (starting > 0) throw new Error(`${starting} services still STARTING at the end of the flight`);
  return `page ${JSON.stringify(state)}, ${marks} timeline marks, ${rows} live services`;
});
