// One of the playground's renderers, each a Web Worker with its own copy of tracer's WebAssembly
// module (tracer.js, built from src/web/playground.cpp), so that typing never waits for them and
// the page needs no shared memory (no cross-origin isolation: any static host serves it). Each
// loads the scene's text, then renders its share of a preview at a quarter of the size and of
// the whole image: the bands of rows whose number is its part, modulo the number of parts.
// Between two bands it reads its messages, so that a newer edit drops the render under way.
/* global importScripts, createTracer */
importScripts("tracer.js");

const PREVIEW_DIVISOR = 4;
const BAND_SAMPLES = 65536; // a band's size, in samples: how soon a newer edit is seen (task2: 55 rows, 8 ms)

let tracer = null; // the module, once instantiated
let playground = null;
let latest = 0; // the newest job's id: an older job stops at its next band
let queued = null; // the newest job not yet started
let running = null;
const reads = []; // files asked for before the module was ready

// Every file under `folder` of the module's file system, by path.
function filesUnder(folder) {
  const found = [];
  for (const name of tracer.FS.readdir(folder)) {
    if (name === "." || name === "..") continue;
    const path = `${folder}/${name}`;
    if (tracer.FS.isDir(tracer.FS.stat(path).mode)) found.push(...filesUnder(path));
    else found.push(path);
  }
  return found;
}

// The gallery's pictures decoded by the browser, without colour conversion, and handed to tracer
// (it has no image library in the browser).
async function providePictures(paths) {
  for (const path of paths.filter((p) => /\.(png|jpe?g)$/i.test(p))) {
    const bitmap = await createImageBitmap(new Blob([tracer.FS.readFile(path)]), {
      colorSpaceConversion: "none",
      premultiplyAlpha: "none",
    });
    const canvas = new OffscreenCanvas(bitmap.width, bitmap.height);
    const context = canvas.getContext("2d");
    context.drawImage(bitmap, 0, 0);
    const rgba = context.getImageData(0, 0, bitmap.width, bitmap.height).data;
    tracer.providePicture(path, bitmap.width, bitmap.height, rgba);
  }
}

// Resolves after the worker has read the messages waiting (faster than setTimeout's 4 ms).
function yieldToMessages() {
  return new Promise((resolve) => {
    const channel = new MessageChannel();
    channel.port1.onmessage = () => resolve();
    channel.port2.postMessage(0);
  });
}

// The rows of each band of a frame: about BAND_SAMPLES samples, at most 64 rows.
function bandRows(frame) {
  return Math.max(1, Math.min(64, Math.round(BAND_SAMPLES / (frame.width * Math.max(frame.samples, 1)))));
}

// Renders this worker's bands of the frame started, posting each; false if a newer job arrived.
async function renderShare(job, frame, final) {
  const rows = bandRows(frame);
  const bands = Math.ceil(frame.height / rows);
  const startedAt = performance.timeOrigin + performance.now();
  let rays = 0;
  for (let band = job.part; band < bands; band += job.parts) {
    const y = band * rows;
    const count = Math.min(rows, frame.height - y);
    const done = playground.renderRows(y, count);
    if (done < 0) throw new Error("the render failed (out of memory?)");
    rays += done;
    const all = playground.pixels(); // a view into the module's memory
    const pixels = new Uint8ClampedArray(all.subarray(y * frame.width * 4, (y + count) * frame.width * 4));
    postMessage({ type: "band", id: job.id, final, y, rows: count, bands, ...frame, pixels }, [pixels.buffer]);
    await yieldToMessages();
    if (latest !== job.id) return false;
  }
  const endedAt = performance.timeOrigin + performance.now();
  postMessage({ type: "share", id: job.id, final, part: job.part, ...frame, startedAt, endedAt, rays });
  return true;
}

// One job: the scene loaded (its diagnostics posted), this worker's share of a preview, then of
// the whole image.
async function run(job) {
  postMessage({ type: "started", id: job.id }); // the page knows this worker has left its older job
  const report = JSON.parse(playground.load(job.path, job.text));
  postMessage({ type: "report", id: job.id, part: job.part, report });
  if (!report.ok) return;
  for (const divisor of [PREVIEW_DIVISOR, 1]) {
    const frame = JSON.parse(playground.start(divisor));
    if (frame.error) {
      postMessage({ type: "failed", id: job.id, message: frame.error });
      return;
    }
    if (!(await renderShare(job, frame, divisor === 1))) return;
  }
}

// Runs the newest queued job, and the next one it left behind, until none is waiting.
async function drain() {
  while (queued) {
    const job = queued;
    queued = null;
    try {
      await run(job);
    } catch (error) {
      postMessage({ type: "failed", id: job.id, message: String(error && error.message ? error.message : error) });
      return; // the page starts a fresh worker: a module that failed may be broken
    }
  }
}

function startDraining() {
  if (tracer && !running) running = drain().finally(() => (running = null));
}

// Posts the text of the file at `path` of the module's file system ("" if there is none).
function readFile(path) {
  let text = "";
  try {
    text = tracer.FS.readFile(path, { encoding: "utf8" });
  } catch {
    text = "";
  }
  postMessage({ type: "file", path, text });
}

onmessage = (event) => {
  const message = event.data;
  if (message.type === "render") {
    latest = message.id;
    queued = message;
    startDraining();
  } else if (message.type === "read") {
    if (tracer) readFile(message.path);
    else reads.push(message.path);
  }
};

createTracer().then(async (module) => {
  tracer = module;
  playground = new tracer.Playground();
  const files = filesUnder("/scenes");
  await providePictures(files);
  postMessage({
    type: "ready",
    scenes: files.filter((path) => path.endsWith(".scn")).sort(),
    language: JSON.parse(tracer.language()),
  });
  for (const path of reads.splice(0)) readFile(path);
  startDraining();
});
