// The browser test of report.html (tests/web/run.sh runs it): headless Chromium (the system's,
// driven by puppeteer-core), no network, the page opened from file://.
//   node tests/web/report_browser.js CHROMIUM DEMO_REPORT HOSTILE_REPORT SCREENSHOT BUDGET_BYTES
// On the demo's page it asserts: no console error or page error and no request leaves the file;
// the WebGL canvas is not blank (pixel variance); moving the slider from the first frame to the
// last changes the image; the shear colours change it; each per-frame plot line has one point
// per summary row; the file is within its budget. On the hostile page (a frame named like an
// <img> tag, a config path holding </script><script>): no dialog, no console error, the strings
// shown as text, no element made from them. Exit 0: passed, 1: failed.
'use strict';
const fs = require('fs');
const path = require('path');
const puppeteer = require(path.join(__dirname, '../../web/node_modules/puppeteer-core'));

const [chromium, demo, hostile, screenshot, budget] = process.argv.slice(2);
let failures = 0;
function check(ok, what) {
  console.log((ok ? 'ok   ' : 'FAIL ') + what);
  if (!ok) failures++;
}

// Pixel statistics of the player's canvas (drawn into a 2-D canvas; the renderer keeps its
// drawing buffer), half by half: variance and a hash of the pixels.
async function canvasStats(page) {
  return page.evaluate(() => {
    const src = document.querySelector('.player-view canvas');
    const c = document.createElement('canvas');
    c.width = src.width;
    c.height = src.height;
    const g = c.getContext('2d');
    g.drawImage(src, 0, 0);
    const d = g.getImageData(0, 0, c.width, c.height).data;
    let sum = 0, sum2 = 0, hash = 0;
    for (let i = 0; i < d.length; i += 4) {
      const y = 0.299 * d[i] + 0.587 * d[i + 1] + 0.114 * d[i + 2];
      sum += y;
      sum2 += y * y;
      hash = (hash * 31 + d[i] + 7 * d[i + 1] + 13 * d[i + 2]) | 0;
    }
    const n = d.length / 4;
    return { variance: sum2 / n - (sum / n) * (sum / n), hash, width: c.width, height: c.height };
  });
}

async function open(browser, file) {
  const page = await browser.newPage();
  const problems = [], dialogs = [], requests = [];
  page.on('console', (m) => { if (m.type() === 'error') problems.push('console: ' + m.text()); });
  page.on('pageerror', (e) => problems.push('page error: ' + e.message));
  page.on('dialog', async (d) => { dialogs.push(d.message()); await d.dismiss(); });
  await page.setRequestInterception(true);
  page.on('request', (r) => {
    if (r.url().startsWith('file://') && r.url().endsWith('.html')) return r.continue();
    requests.push(r.url());
    return r.abort();
  });
  await page.setViewport({ width: 1280, height: 900 });
  await page.goto('file://' + path.resolve(file), { waitUntil: 'load' });
  await new Promise((r) => setTimeout(r, 500));
  return { page, problems, dialogs, requests };
}

async function nextFrames(page) {
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
}

async function main() {
  const browser = await puppeteer.launch({
    executablePath: chromium,
    headless: true,
    args: ['--no-sandbox', '--use-gl=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist',
      '--disable-background-networking', '--disable-component-update', '--disable-sync',
      '--no-first-run', '--disable-default-apps', '--proxy-server=127.0.0.1:9', '--proxy-bypass-list=<-loopback>'],
  });
  try {
    // --- The demo.
    const size = fs.statSync(demo).size;
    check(size <= Number(budget), `demo report.html is ${size} bytes, within the budget of ${budget}`);
    const d = await open(browser, demo);
    const { page } = d;
    const hasPlayer = await page.evaluate(() => !!document.querySelector('.player-view canvas'));
    check(hasPlayer, 'the page has the 3D player');
    if (hasPlayer) {
      // It plays on opening; pause it, back to the first frame.
      const playing = await page.evaluate(() => {
        const b = document.querySelector('.player-controls button.play');
        const was = b.textContent === 'Pause';
        if (was) b.click();
        const s = document.querySelector('.player-controls input[type=range]');
        s.value = '0';
        s.dispatchEvent(new Event('input'));
        return was;
      });
      check(playing, 'the player plays on opening');
      await nextFrames(page);
      const first = await canvasStats(page);
      check(first.variance > 20, `the WebGL canvas is not blank (pixel variance ${first.variance.toFixed(1)})`);
      const last = await page.evaluate(() => {
        const s = document.querySelector('.player-controls input[type=range]');
        s.value = s.max;
        s.dispatchEvent(new Event('input'));
        return Number(s.max);
      });
      await nextFrames(page);
      const atLast = await canvasStats(page);
      check(last > 0 && atLast.hash !== first.hash, `moving the slider to the last frame (${last}) changes the image`);
      await page.screenshot({ path: screenshot, clip: await page.evaluate(() => {
        const r = document.getElementById('player').getBoundingClientRect();
        return { x: r.x, y: r.y + window.scrollY, width: r.width, height: Math.min(r.height, 620) };
      }) });
      await page.evaluate(() => {
        const m = document.querySelector('.player-controls select.mode');
        m.value = 'shear';
        m.dispatchEvent(new Event('change'));
      });
      await nextFrames(page);
      const shear = await canvasStats(page);
      check(shear.hash !== atLast.hash, 'switching to the shear colours changes the image');
    }
    const plot = await page.evaluate(() => {
      const rows = document.querySelectorAll('table.summary tbody tr').length;
      const lines = Array.from(document.querySelectorAll('svg.chart polyline.series'));
      return { rows, points: lines.map((l) => l.getAttribute('points').trim().split(/\s+/).length) };
    });
    check(plot.points.length > 0 && plot.rows > 0 && plot.points.every((p) => p === plot.rows),
      `every plot line has one point per frame (${plot.rows} frames; ${plot.points.join(', ')} points)`);
    check(d.problems.length === 0, 'no console error on the demo' + (d.problems.length ? ': ' + d.problems.join('; ') : ''));
    check(d.requests.length === 0, 'no request leaves the file' + (d.requests.length ? ': ' + d.requests.join(', ') : ''));
    await page.close();

    // --- The hostile strings.
    const h = await open(browser, hostile);
    const text = await h.page.evaluate(() => ({
      body: document.body.innerText,
      images: document.querySelectorAll('img').length,
      scripts: document.querySelectorAll('script').length,
    }));
    check(h.dialogs.length === 0, 'no dialog on the hostile page' + (h.dialogs.length ? ': ' + h.dialogs.join(', ') : ''));
    check(h.problems.length === 0, 'no console error on the hostile page' + (h.problems.length ? ': ' + h.problems.join('; ') : ''));
    check(text.body.includes('<img src=x onerror=alert(1)>.obj'), 'the hostile frame name is shown as text');
    check(text.body.includes('</script><script>alert(1)</script>'), 'the hostile config path is shown as text');
    check(text.images === 0, 'no <img> element was made from the frame name');
    await h.page.close();
  } finally {
    await browser.close();
  }
  console.log(failures ? `report browser test: ${failures} FAILED` : 'report browser test: passed');
  process.exit(failures ? 1 : 0);
}

main().catch((e) => {
  console.error('report browser test: error: ' + (e && e.stack ? e.stack : e));
  process.exit(1);
});
