// demo.js - runs demo.wasm (examples/web/demo_web.c) in demo.html: one simulated 1/30 s frame
// per 1/30 s of wall time (within 80 % of it, else slow motion), drawn into the canvas; keys,
// buttons and the pointer passed on. ?scripted=1&frames=N replays the terminal demo's headless
// run instead (no wall budget, deterministic) for N frames, back to back, and then shows the
// checksum and the frame times in document.title and #result (make test-web reads them).
'use strict';
(async function () {
  const params = new URLSearchParams(location.search);
  const scripted = params.get('scripted') === '1';
  const frames = scripted ? Math.max(1, parseInt(params.get('frames') || '600', 10)) : Infinity;
  const tank = params.get('scene') === 'tank' ? 1 : 0;
  const FPS = 30;
  const $ = (id) => document.getElementById(id);
  let memory = null;
  const text = (pointer) => { // a NUL-terminated string of the module's memory
    const bytes = new Uint8Array(memory.buffer, pointer);
    return new TextDecoder().decode(bytes.subarray(0, bytes.indexOf(0)));
  };
  // The WASI calls wasi-libc makes: stderr lines go to the console; the rest are refused (ENOSYS).
  const wasi = {
    fd_write(fd, iovs, count, written) {
      const view = new DataView(memory.buffer);
      let s = '', total = 0;
      for (let k = 0; k < count; ++k) {
        const at = view.getUint32(iovs + 8 * k, true), length = view.getUint32(iovs + 8 * k + 4, true);
        s += new TextDecoder().decode(new Uint8Array(memory.buffer, at, length));
        total += length;
      }
      view.setUint32(written, total, true);
      console.warn(s.trimEnd());
      return 0;
    },
  };
  const module = await WebAssembly.compileStreaming(fetch('demo.wasm'));
  const imports = { env: { now_seconds: () => performance.now() / 1000 }, wasi_snapshot_preview1: wasi };
  for (const i of WebAssembly.Module.imports(module)) {
    if (i.kind === 'function' && !(imports[i.module] && imports[i.module][i.name])) imports[i.module][i.name] = () => 52;
  }
  const wasm = (await WebAssembly.instantiate(module, imports)).exports;
  memory = wasm.memory;
  wasm._initialize();
  if (wasm.web_start(tank, scripted ? 1 : 0) !== 0) throw new Error('web_start: ' + text(wasm.web_error()));

  const canvas = $('view'), context = canvas.getContext('2d');
  const image = context.createImageData(wasm.web_width(), wasm.web_height());
  const times = []; // [ms] of each frame: physics and picture (web_frame)
  let frame = 0, paused = false, pendingKey = -1, next = performance.now(), startup = 0, failed = '';

  const press = (key) => {
    if (key === 'p') { paused = !paused; $('pause').textContent = paused ? 'resume' : 'pause'; return; }
    if (!scripted && ' fghjklt'.includes(key)) pendingKey = key.charCodeAt(0);
  };
  document.addEventListener('keydown', (e) => { if (e.key.length === 1 && !e.ctrlKey && !e.metaKey) { press(e.key); e.preventDefault(); } });
  $('drop').onclick = () => press(' ');
  $('shear').onclick = () => press('f');
  $('scene').onclick = () => press('t');
  $('pause').onclick = () => press('p');
  const pointer = (kind) => (e) => { // canvas pixels from the event's CSS pixels
    if (scripted) return;
    const box = canvas.getBoundingClientRect();
    const x = (e.clientX - box.left) * canvas.width / box.width, y = (e.clientY - box.top) * canvas.height / box.height;
    if (kind === 0) canvas.setPointerCapture(e.pointerId);
    wasm.web_pointer(kind, x, y);
    e.preventDefault();
  };
  canvas.addEventListener('pointerdown', pointer(0));
  canvas.addEventListener('pointermove', pointer(1));
  canvas.addEventListener('pointerup', pointer(2));
  canvas.addEventListener('pointercancel', pointer(2));

  const median = (v) => { const s = [...v].sort((a, b) => a - b); return s.length ? s[s.length >> 1] : 0; };
  function finish() {
    const sorted = [...times].sort((a, b) => a - b);
    const result = {
      checksum: BigInt.asUintN(64, wasm.web_checksum()).toString(16).padStart(16, '0'), frames: frame, failed,
      median_ms: +median(times).toFixed(2), worst_ms: +(sorted[sorted.length - 1] || 0).toFixed(2),
      worst_frame: times.indexOf(sorted[sorted.length - 1]), worst_after_first_30_ms: +Math.max(0, ...times.slice(30)).toFixed(2),
      startup_ms: +startup.toFixed(1), status: text(wasm.web_status()),
    };
    $('result').textContent = JSON.stringify(result);
    document.title = 'done ' + JSON.stringify(result);
  }
  function tick(now) {
    if (scripted || (!paused && now >= next)) {
      const t0 = performance.now();
      const r = wasm.web_frame(frame, pendingKey, scripted ? 0 : 0.8 / FPS);
      times.push(performance.now() - t0);
      if (times.length > 60 && !scripted) times.shift();
      pendingKey = -1;
      if (r !== 0) failed = text(wasm.web_error());
      image.data.set(new Uint8Array(memory.buffer, wasm.web_pixels(), image.data.length));
      context.putImageData(image, 0, 0);
      if (++frame === 1) startup = performance.now(); // from the navigation's start
      next = Math.max(next + 1000 / FPS, performance.now()); // a late frame shifts the schedule: no catch-up burst
      $('status').textContent = text(wasm.web_status());
      $('shear-name').textContent = text(wasm.web_formulation());
      $('frame').textContent = `frame ${times[times.length - 1].toFixed(1)} ms (median of the last ${Math.min(times.length, 60)}: ` +
        `${median(times.slice(-60)).toFixed(1)} ms; budget ${(1000 / FPS).toFixed(1)} ms)`;
      $('message').textContent = failed || text(wasm.web_message());
      if (failed || frame >= frames) return finish();
    }
    requestAnimationFrame(tick);
  }
  requestAnimationFrame(tick);
})().catch((e) => { document.title = 'error ' + e; document.getElementById('result').textContent = 'error ' + e; });
