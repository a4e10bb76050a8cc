// The browser test of karman's page (run by `cargo xtask web-test`): headless Chromium opens
// the built page from a loopback server, and every figure the page shows or lets download is
// compared with the command-line program's, byte for byte. Screenshots after each step go to
// KARMAN_SCREENSHOTS.
//
// Environment: KARMAN_SITE (the built page), KARMAN_CLI (the karman binary), KARMAN_ROOT (the
// repository), KARMAN_SCREENSHOTS, KARMAN_CHROMIUM (the browser).
import { chromium } from "playwright-core";
import { execFileSync } from "node:child_process";
import { createServer } from "node:http";
import { mkdtempSync, readFileSync, writeFileSync, copyFileSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { join, extname, normalize } from "node:path";

const site = process.env.KARMAN_SITE;
const cli = process.env.KARMAN_CLI;
const root = process.env.KARMAN_ROOT;
const shots = process.env.KARMAN_SCREENSHOTS;
const fixtures = join(root, "fixtures");
const failures = [];

function expect(condition, what) {
  if (condition) {
    console.log(`ok: ${what}`);
  } else {
    console.log(`FAILED: ${what}`);
    failures.push(what);
  }
}

function karman(args, options = {}) {
  return execFileSync(cli, args, { encoding: "utf8", maxBuffer: 1 << 28, ...options });
}

// `karman args`, expected to fail: its stderr.
function karmanFails(args) {
  try {
    karman(args, { stdio: ["ignore", "pipe", "pipe"] });
  } catch (e) {
    return String(e.stderr);
  }
  throw new Error(`karman ${args.join(" ")} succeeded`);
}

// The static server: the site's files, on loopback.
const TYPES = { ".html": "text/html", ".js": "text/javascript", ".css": "text/css" };
const server = createServer((req, res) => {
  let path = normalize(decodeURIComponent(new URL(req.url, "http://x").pathname)).replace(/^(\.\.[/\\])+/, "");
  if (path.endsWith("/")) { path += "index.html"; }
  try {
    const body = readFileSync(join(site, path));
    res.writeHead(200, { "content-type": TYPES[extname(path)] || "application/octet-stream" });
    res.end(body);
  } catch (_) {
    res.writeHead(404);
    res.end();
  }
});
await new Promise((r) => server.listen(0, "127.0.0.1", r));
const url = `http://127.0.0.1:${server.address().port}/`;

const profile = mkdtempSync(join(tmpdir(), "karman-chromium-"));
const scratch = mkdtempSync(join(tmpdir(), "karman-web-test-"));
const context = await chromium.launchPersistentContext(profile, {
  executablePath: process.env.KARMAN_CHROMIUM || "/usr/bin/chromium",
  headless: true,
  acceptDownloads: true,
  args: [
    "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync",
  ],
});
const page = context.pages()[0] || (await context.newPage());
page.on("pageerror", (e) => console.log(`page error: ${e.message}`));
let step = 0;
async function shot(name) {
  step += 1;
  await page.screenshot({ path: join(shots, `${String(step).padStart(2, "0")}-${name}.png`), fullPage: true });
}

async function load(mission, others) {
  await page.evaluate(() => { document.getElementById("status").textContent = ""; });
  await page.locator("#file-input").setInputFiles([mission, ...others]);
  await page.waitForFunction((n) => document.getElementById("status").textContent === `${n} file(s) read`, others.length + 1);
}

// Downloads what the button `id` offers; its text.
async function download(id) {
  const [file] = await Promise.all([page.waitForEvent("download"), page.click(id)]);
  const path = join(scratch, `${id.slice(1)}-${step}`);
  await file.saveAs(path);
  return readFileSync(path, "utf8");
}

async function flyAndWait() {
  await page.evaluate(() => { document.getElementById("status").textContent = ""; });
  await page.click("#fly");
  await page.waitForFunction(() => ["flown", "the flight failed"].includes(document.getElementById("status").textContent), null, { timeout: 120000 });
  return page.textContent("#status");
}

const KEYS = ["apogee_agl_m", "out_of_rail_velocity_mps", "impact_x_m", "impact_y_m"];

async function compareFlight(label, missionPath) {
  const status = await flyAndWait();
  expect(status === "flown", `${label}: the page flies it (${status})`);
  const cliText = karman(["simulate", missionPath, "--json"]);
  const cliJson = JSON.parse(cliText);
  for (const key of KEYS) {
    const shown = await page.textContent(`#summary tr[data-key="${key}"] td`);
    expect(shown === String(cliJson[key]), `${label}: ${key} in the page ${shown} = CLI ${cliJson[key]}`);
  }
  const pageJson = await page.textContent("#json");
  expect(pageJson === cliText.trimEnd(), `${label}: the page's --json text is the CLI's, byte for byte`);
}

try {
  await page.goto(url);
  await page.waitForFunction(() => typeof wasm_bindgen.Files === "function" && document.readyState === "complete");
  await shot("opened");

  // 1. The example mission, flown, its figures and downloads the CLI's.
  const example = join(fixtures, "example.toml");
  const exampleFiles = ["example_K1960.eng", "power_off_drag.csv", "power_on_drag.csv"].map((f) => join(fixtures, f));
  await load(example, exampleFiles);
  await compareFlight("example.toml", example);
  const out = join(scratch, "example-out");
  karman(["simulate", example, "--out", out]);
  for (const [id, file] of [["#download-summary", "summary.json"], ["#download-trajectory", "trajectory.csv"], ["#download-kml", "flight.kml"]]) {
    const got = await download(id);
    expect(got === readFileSync(join(out, file), "utf8"), `example.toml: the downloaded ${file} is the CLI's --out ${file}`);
  }
  await shot("example-flown");

  // 2. A typo: the error at its line and column, as `karman check` reports it.
  const text = readFileSync(example, "utf8");
  const typo = text.replace("\nmotor_position = 1.60", "\nmotor_positon = 1.60");
  expect(typo !== text, "the typo is made");
  const typoDir = join(scratch, "typo");
  execFileSync("mkdir", ["-p", typoDir]);
  writeFileSync(join(typoDir, "typo.toml"), typo);
  for (const f of exampleFiles) { copyFileSync(f, join(typoDir, f.split("/").pop())); }
  const cliError = karmanFails(["check", join(typoDir, "typo.toml")]);
  const located = /typo\.toml:(\d+):(\d+)/.exec(cliError);
  expect(located !== null, `the CLI locates the typo: ${cliError.split("\n").slice(0, 3).join(" | ")}`);
  await page.fill("#mission-name", "typo.toml");
  await page.fill("#mission", typo);
  await page.click("#check");
  await page.waitForSelector("#errors li.error");
  const first = await page.locator("#errors li.error").first();
  const [line, column, message] = [await first.getAttribute("data-line"), await first.getAttribute("data-column"), await first.textContent()];
  expect(located && line === located[1] && column === located[2], `the page shows the typo at ${line}:${column} (CLI ${located && located.slice(1, 3).join(":")})`);
  expect(message.includes("motor_positon") && cliError.includes(message), `the page's message is the CLI's line: ${message}`);
  await first.click();
  await shot("typo");

  // 3. Bad input: a binary mission, a missing data file; the page stays usable.
  const binary = join(scratch, "binary.toml");
  writeFileSync(binary, Buffer.from([0x6e, 0x61, 0x6d, 0x65, 0xff, 0xfe, 0x00, 0x01]));
  await page.locator("#file-input").setInputFiles([binary]);
  await page.waitForSelector("#errors li.error");
  expect((await page.textContent("#errors")).includes("binary.toml: not a UTF-8 text file"), "a binary mission: a clear message");
  await page.fill("#mission-name", "example.toml");
  await page.fill("#mission", text.replace('thrust = "example_K1960.eng"', 'thrust = "missing_K1960.eng"'));
  expect((await flyAndWait()) === "the flight failed", "a mission naming a file not given: the flight fails");
  const missing = await page.textContent("#errors");
  expect(missing.includes("missing_K1960.eng") && missing.includes("not among the given files"), `... with a message naming the file: ${missing.slice(0, 160)}`);
  await shot("bad-input");
  await page.fill("#mission", text);
  expect((await flyAndWait()) === "flown", "the page still flies afterwards");

  // 4. The Calisto flight: the CLI's figures, and the time in the page against the native one.
  const calisto = join(fixtures, "validation/calisto/mission.toml");
  const calistoFiles = ["Cesaroni_M1670.eng", "powerOffDragCurve.csv", "powerOnDragCurve.csv", "NACA0012-radians.txt"].map((f) => join(fixtures, "validation/calisto", f));
  await load(calisto, calistoFiles);
  await compareFlight("calisto", calisto);
  let pageMs = Infinity;
  for (let i = 0; i < 5; i++) {
    await flyAndWait();
    pageMs = Math.min(pageMs, parseFloat(await page.getAttribute("#timing", "data-ms")));
  }
  let nativeMs = Infinity;
  for (let i = 0; i < 5; i++) {
    const t0 = process.hrtime.bigint();
    karman(["simulate", calisto, "--json"]);
    nativeMs = Math.min(nativeMs, Number(process.hrtime.bigint() - t0) / 1e6);
  }
  console.log(`timing: Calisto flight ${pageMs.toFixed(1)} ms in the page, ${nativeMs.toFixed(1)} ms native (the whole \`karman simulate --json\` process), ratio ${(pageMs / nativeMs).toFixed(2)}`);
  await shot("calisto");

  // 5. A 200-sample Monte Carlo study in workers: the CLI's samples.csv, byte for byte.
  await load(example, exampleFiles);
  await page.fill("#mc-samples", "200");
  const t0 = Date.now();
  await page.click("#mc-run");
  await page.waitForSelector("#mc-status[data-done]", { timeout: 600000 });
  console.log(`timing: 200 samples in the page: ${(Date.now() - t0) / 1000} s (${await page.textContent("#mc-status")})`);
  const samples = await download("#mc-download");
  const mcOut = join(scratch, "mc");
  karman(["montecarlo", example, "--samples", "200", "--out", mcOut, "--quiet"]);
  const cliSamples = readFileSync(join(mcOut, "samples.csv"), "utf8");
  expect(samples === cliSamples, `the page's samples.csv (${samples.length} bytes) is the CLI's (${cliSamples.length} bytes)`);
  expect((await page.locator("#mc-plot circle").count()) > 150, "the landing points are drawn");
  await shot("montecarlo");
} catch (e) {
  console.log(`FAILED: ${e.stack || e}`);
  failures.push(String(e));
  await shot("failure").catch(() => {});
} finally {
  await context.close();
  server.close();
  rmSync(profile, { recursive: true, force: true });
  rmSync(scratch, { recursive: true, force: true });
}

if (failures.length) {
  console.log(`${failures.length} failure(s)`);
  process.exit(1);
}
console.log("the page agrees with the CLI");
