// web_run.js DIR FRAMES SHOT [PAGE_SHOT] - opens DIR/demo.html?scripted=1&frames=FRAMES in headless
// Chromium (CHROMIUM, default chromium) served from 127.0.0.1 by this script (no other network),
// waits until the page shows its result in document.title, prints the result (JSON: checksum,
// frame times, start-up) on stdout, and writes the canvas as shown to SHOT (PNG) and, if given,
// the whole page to PAGE_SHOT. Talks to the browser over --remote-debugging-pipe (the DevTools
// protocol as NUL-ended JSON on file descriptors 3 and 4): no WebSocket, no npm package.
// Node's own modules only; used by tests/web_check.sh (make test-web).
'use strict';
const { spawn } = require('child_process');
const fs = require('fs');
const http = require('http');
const os = require('os');
const path = require('path');

const [dir, framesArg, shot, pageShot] = process.argv.slice(2);
if (!dir || !framesArg || !shot) { console.error('usage: node web_run.js DIR FRAMES SHOT [PAGE_SHOT]'); process.exit(2); }
const TIMEOUT_S = 900; // 600 frames take about 40 s on one busy core; a hang ends here
const types = { '.html': 'text/html', '.js': 'text/javascript', '.wasm': 'application/wasm' };

const server = http.createServer((req, res) => {
  const name = path.basename(new URL(req.url, 'http://x').pathname);
  const file = path.join(dir, name);
  if (!types[path.extname(name)] || !fs.existsSync(file)) { res.writeHead(404); res.end(); return; }
  res.writeHead(200, { 'Content-Type': types[path.extname(name)] });
  res.end(fs.readFileSync(file));
});

function fail(message) { console.error('web_run: ' + message); process.exit(1); }

server.listen(0, '127.0.0.1', () => {
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'web_run_'));
  const browser = spawn(process.env.CHROMIUM || 'chromium', ['--headless=new', '--no-sandbox', '--disable-gpu', '--no-first-run',
    '--disable-extensions', '--disable-background-networking', '--disable-dev-shm-usage', '--remote-debugging-pipe', '--user-data-dir=' + profile, 'about:blank'],
  { stdio: ['ignore', 'ignore', 'pipe', 'pipe', 'pipe'] });
  let stderr = '';
  browser.stderr.on('data', (d) => { stderr += d; });
  browser.on('exit', (code) => { if (!done) fail('chromium exited (' + code + ') before the page finished:\n' + stderr.slice(-2000)); });
  const toBrowser = browser.stdio[3], fromBrowser = browser.stdio[4];
  let id = 0, buffer = '', done = false;
  const waiting = new Map();
  fromBrowser.on('data', (d) => {
    buffer += d;
    let end;
    while ((end = buffer.indexOf('\0')) >= 0) {
      const message = JSON.parse(buffer.slice(0, end));
      buffer = buffer.slice(end + 1);
      if (message.id && waiting.has(message.id)) {
        const { resolve, reject } = waiting.get(message.id);
        waiting.delete(message.id);
        if (message.error) reject(new Error(JSON.stringify(message.error))); else resolve(message.result);
      }
    }
  });
  const send = (method, params = {}, sessionId) => new Promise((resolve, reject) => {
    waiting.set(++id, { resolve, reject });
    toBrowser.write(JSON.stringify({ id, method, params, sessionId }) + '\0');
  });
  const timer = setTimeout(() => fail('no result after ' + TIMEOUT_S + ' s'), TIMEOUT_S * 1000);

  (async () => {
    const { targetId } = await send('Target.createTarget', { url: 'about:blank' });
    const { sessionId } = await send('Target.attachToTarget', { targetId, flatten: true });
    const page = (method, params) => send(method, params, sessionId);
    // 624 CSS pixels wide: the canvas (600 wide, 12 px margins) shows at its own size, unscaled
    await page('Emulation.setDeviceMetricsOverride', { width: 624, height: 620, deviceScaleFactor: 1, mobile: false });
    await page('Page.enable');
    const url = `http://127.0.0.1:${server.address().port}/demo.html?scripted=1&frames=${parseInt(framesArg, 10)}`;
    await page('Page.navigate', { url });
    let title = '';
    while (!/^(done|error)/.test(title)) {
      await new Promise((r) => setTimeout(r, 250));
      title = (await page('Runtime.evaluate', { expression: 'document.title', returnByValue: true })).result.value || '';
    }
    if (title.startsWith('error')) fail(title);
    const box = (await page('Runtime.evaluate', {
      expression: 'JSON.stringify((({x, y, width, height}) => ({x, y, width, height}))(document.getElementById("view").getBoundingClientRect()))',
      returnByValue: true })).result.value;
    const clip = Object.assign(JSON.parse(box), { scale: 1 });
    fs.writeFileSync(shot, Buffer.from((await page('Page.captureScreenshot', { format: 'png', clip })).data, 'base64'));
    if (pageShot) fs.writeFileSync(pageShot, Buffer.from((await page('Page.captureScreenshot', { format: 'png' })).data, 'base64'));
    console.log(title.replace(/^done /, ''));
    done = true;
    clearTimeout(timer);
    const exited = new Promise((r) => browser.on('exit', r));
    await send('Browser.close').catch(() => {});
    await Promise.race([exited, new Promise((r) => setTimeout(r, 5000))]);
    server.close();
    fs.rmSync(profile, { recursive: true, force: true, maxRetries: 3 });
  })().catch((e) => fail(e.stack || String(e)));
});
