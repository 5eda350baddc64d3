// The playground's renderer, in a Web Worker of its own so that typing never waits for it: tracer's
// WebAssembly module (tracer.js, built from src/web/playground.cpp) loads the scene's text, then
// renders a preview at a quarter of its size and the full image, a band of rows at a time. Between
// two bands it reads its messages, so a newer edit drops the render under way at once.
/* global importScripts, createTracer */
importScripts("tracer.js");

const PREVIEW_DIVISOR = 4;
const BAND_MS = 25; // a band's target time: how soon a newer edit is seen

let tracer = null; // the module, once instantiated
let playground = null;
let latest = 0; // the newest job's id: an older job stops at its next band
let queued = null; // the newest job not yet started

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

// The gallery's pictures decoded by the browser and handed to tracer (it has no image library).
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

// Renders the frame started, band by band; false if a newer job arrived first.
async function renderFrame(job, frame, final) {
  let rows = 4;
  let rays = 0;
  const started = performance.now();
  for (let y = 0; y < frame.height; ) {
    const bandStarted = performance.now();
    const done = playground.renderRows(y, rows);
    if (done < 0) throw new Error("the render failed (out of memory?)");
    rays += done;
    y += rows;
    const took = performance.now() - bandStarted;
    rows = Math.max(1, Math.min(256, Math.round((rows * BAND_MS) / Math.max(took, 1))));
    postMessage({ type: "progress", id: job.id, final, fraction: Math.min(y / frame.height, 1) });
    await yieldToMessages();
    if (latest !== job.id) return false;
  }
  const pixels = new Uint8ClampedArray(playground.pixels()); // a copy: the module's memory may move
  postMessage(
    {
      type: "image",
      id: job.id,
      final,
      width: frame.width,
      height: frame.height,
      pixels,
      milliseconds: performance.now() - started,
      rays,
    },
    [pixels.buffer],
  );
  return true;
}

// One job: the scene loaded (its diagnostics posted), a preview, then the whole image.
async function run(job) {
  const loadStarted = performance.now();
  const report = JSON.parse(playground.load(job.path, job.text));
  postMessage({ type: "report", id: job.id, report, milliseconds: performance.now() - loadStarted });
  if (!report.ok) return;
  for (const divisor of job.preview === false ? [1] : [PREVIEW_DIVISOR, 1]) {
    const frame = JSON.parse(playground.start(divisor));
    if (frame.error) {
      postMessage({ type: "failed", id: job.id, message: frame.error });
      return;
    }
    if (!(await renderFrame(job, frame, divisor === 1))) return;
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
      playground = new tracer.Playground(); // a fresh start after a failure
    }
  }
}

let running = null;
onmessage = (event) => {
  const message = event.data;
  if (message.type === "render") {
    latest = message.id;
    queued = message;
    if (tracer && !running) running = drain().finally(() => (running = null));
  } else if (message.type === "read") {
    if (tracer) readFile(message.path);
    else reads.push(message.path);
  }
};

const reads = []; // files asked for before the module was ready

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
  if (queued && !running) running = drain().finally(() => (running = null));
});
