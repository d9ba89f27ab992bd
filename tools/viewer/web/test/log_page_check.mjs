// Opens mmh-viewer --log's page in headless Chromium (Debian's, driven by playwright-core) and
// scrubs the recorded flight with the time slider: at the end the whole flight is there (goal
// reached, every decision, the debug layer when the planners published it); in the middle less
// of the map, the path and the decisions; at the end again exactly what it showed the first
// time; then play runs the time on. Takes a screenshot in the middle of the flight.
//   node log_page_check.mjs http://127.0.0.1:8766/ OUT.png EXPECT_DEBUG(0|1) TIMEOUT_S
import { runPageCheck } from "./browser.mjs";

const [url, screenshot, expectDebugText = "0", timeoutText = "30"] = process.argv.slice(2);
const expectDebug = expectDebugText === "1";
const timeout = Number(timeoutText) * 1000;

const state = (page) => page.evaluate(() => ({ ...document.body.dataset }));

// Moves the slider to the fraction f of the flight as a user would (input, then change) and
// waits until the page shows the scene of that time: a new generation, its time, and ready (the
// server sends it after the snapshots; the page then writes its counts at once).
async function scrub(page, f) {
  const before = await state(page);
  const target = await page.evaluate((fraction) => {
    const s = document.getElementById("playback-slider");
    const t = Number(s.min) + fraction * (Number(s.max) - Number(s.min));
    s.value = String(t);
    s.dispatchEvent(new Event("input", { bubbles: true }));
    s.dispatchEvent(new Event("change", { bubbles: true }));
    return Number(s.value);
  }, f);
  await page.waitForFunction(
    ([generation, t]) => {
      const d = document.body.dataset;
      return d.generation !== generation && d.readyGeneration === d.generation &&
        Math.abs(Number(d.playbackTime) - t) < 0.01;
    },
    [before.generation, target],
    { timeout, polling: 100 },
  );
  return state(page);
}

await runPageCheck(url, async (page) => {
  await page.waitForFunction(
    () => document.body.dataset.connection === "connected" && document.body.dataset.playback === "log" &&
      document.body.dataset.generation !== undefined,
    null,
    { timeout, polling: 100 },
  );
  if (!(await page.locator("#playback").isVisible())) throw new Error("no time slider shown");

  const end = await scrub(page, 1.0);
  if (end.mission !== "goal reached") throw new Error(`at the end the mission is ${end.mission}`);
  if (!(+end.voxels >= 100 && +end.trajectories >= 1 && +end.decisions >= 1 && +end.pathPoints >= 10))
    throw new Error(`at the end: ${JSON.stringify(end)}`);
  const endMarks = await page.locator("#timeline .mark").count();
  if (endMarks !== +end.decisions) throw new Error(`${endMarks} timeline marks for ${end.decisions} decisions`);
  const debugShown = +end.debugPolytopes + +end.debugPaths + +end.debugPairs;
  if (expectDebug && !(+end.debugPaths >= 1)) throw new Error(`no debug layer: ${JSON.stringify(end)}`);
  if (!expectDebug && debugShown !== 0) throw new Error(`a debug layer without debug publishing: ${JSON.stringify(end)}`);

  const middle = await scrub(page, 0.5);
  for (const key of ["decisions", "pathPoints", "trajectories"]) {
    if (!(+middle[key] < +end[key])) throw new Error(`${key}: ${middle[key]} in the middle, ${end[key]} at the end`);
  }
  if (!(+middle.voxels <= +end.voxels)) throw new Error(`more voxels in the middle (${middle.voxels}) than at the end`);
  if (middle.mission === "goal reached") throw new Error("the goal is reached in the middle of the flight");
  const middleMarks = await page.locator("#timeline .mark").count();
  if (middleMarks !== +middle.decisions) throw new Error(`${middleMarks} marks for ${middle.decisions} decisions`);
  await page.locator("#timeline .mark").last().click();
  const details = await page.locator("#decision").innerText();
  if (!/Decision #\d+/.test(details)) throw new Error(`no decision details: ${details}`);
  await page.screenshot({ path: screenshot });

  const again = await scrub(page, 1.0);
  for (const key of ["voxels", "pathPoints", "trajectories", "decisions", "debugPolytopes", "debugPaths", "debugPairs", "mission"]) {
    if (again[key] !== end[key]) throw new Error(`${key}: ${again[key]} at the end again, ${end[key]} the first time`);
  }

  // Play from a quarter of the flight: the time runs on and the path grows.
  const quarter = await scrub(page, 0.25);
  await page.locator("#playback-play").click();
  await page.waitForFunction(
    ([t, points]) => Number(document.body.dataset.playbackTime) > t + 0.5 && +document.body.dataset.pathPoints > points,
    [Number(quarter.playbackTime), +quarter.pathPoints],
    { timeout, polling: 100 },
  );
  await page.locator("#playback-play").click(); // pause
  await page.waitForFunction(() => document.body.dataset.playing === "false", null, { timeout, polling: 100 });
  return `log page; end ${JSON.stringify(end)}; middle ${JSON.stringify(middle)}`;
});
