// What the browser checks share: Debian's headless Chromium (driven by playwright-core) with a
// software GPU, one page of the given viewport whose errors are collected, and the verdict: the
// check's text on success, its error otherwise, and the exit code.
import { existsSync } from "node:fs";
import { chromium } from "playwright-core";

export async function runPageCheck(url, check) {
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
    const text = await check(page);
    if (errors.length) throw new Error(`page errors: ${errors.join("; ")}`);
    console.log(`ok: ${text}`);
    code = 0;
  } catch (e) {
    console.log(`FAIL: ${e.message}`);
    if (errors.length) console.log(`page errors: ${errors.join("; ")}`);
  } finally {
    await browser.close();
  }
  process.exit(code);
}
