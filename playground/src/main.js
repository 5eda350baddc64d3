// The playground's page: the editor (CodeMirror 6) with tracer's highlighting, completion, hover and
// diagnostics, the image the worker renders as you type (a preview, then the whole image), the
// gallery, share links that carry the scene in the URL's fragment, and the PNG download.
import { autocompletion, closeBrackets, closeBracketsKeymap, completionKeymap } from "@codemirror/autocomplete";
import { defaultKeymap, history, historyKeymap, indentWithTab } from "@codemirror/commands";
import { bracketMatching, defaultHighlightStyle, indentOnInput, syntaxHighlighting } from "@codemirror/language";
import { lintGutter, setDiagnostics } from "@codemirror/lint";
import { highlightSelectionMatches, searchKeymap } from "@codemirror/search";
import { EditorState } from "@codemirror/state";
import {
  drawSelection,
  EditorView,
  highlightActiveLine,
  highlightActiveLineGutter,
  hoverTooltip,
  keymap,
  lineNumbers,
} from "@codemirror/view";
import { Language, sceneLanguage } from "./language.js";
import { readShareLink, shareLink } from "./share.js";

const EDIT_PAUSE_MS = 40; // typing pauses this long before the scene is rendered again
const DEFAULT_SCENE = "/scenes/task2.scn";

const canvas = document.getElementById("image");
const statusLine = document.getElementById("status");
const progress = document.getElementById("progress");
const diagnosticsPanel = document.getElementById("diagnostics");
const gallery = document.getElementById("gallery");

let language = null; // tracer's tables, from the worker
let scenePath = DEFAULT_SCENE; // the file the text stands for: relative paths start from its folder
let jobs = 0; // the last render job's id
let editedAt = 0; // when the last edit was made (the status line's edit-to-preview time)
let renderTimer = 0;
let lastJob = null;

// The editor: the language's highlighting, completion and hover, tracer's diagnostics in place.
const view = new EditorView({
  parent: document.getElementById("editor"),
  state: EditorState.create({
    doc: "",
    extensions: [
      lineNumbers(),
      highlightActiveLineGutter(),
      history(),
      drawSelection(),
      indentOnInput(),
      bracketMatching(),
      closeBrackets(),
      highlightActiveLine(),
      highlightSelectionMatches(),
      sceneLanguage,
      syntaxHighlighting(defaultHighlightStyle, { fallback: true }),
      autocompletion({ override: [complete] }),
      hoverTooltip(hover),
      lintGutter(),
      keymap.of([
        ...closeBracketsKeymap,
        ...defaultKeymap,
        ...searchKeymap,
        ...historyKeymap,
        ...completionKeymap,
        indentWithTab,
      ]),
      EditorView.updateListener.of((update) => {
        if (update.docChanged) scheduleRender();
      }),
    ],
  }),
});

// What the page drew (job id, final or preview, size), and the editor: for the browser tests.
const drawn = [];
const firstPaints = []; // {id, at}: when each job's first pixels were on screen
let restarts = 0; // workers replaced (stuck on an older job, or failed)
window.tracerPlayground = {
  view,
  drawn,
  jobs: () => jobs,
  jobText: () => lastJob && lastJob.text,
  restarts: () => restarts,
  firstPaints,
};

function complete(context) {
  if (!language) return null;
  const found = language.completions(context.state.doc.toString(), context.pos);
  if (!found.entries.length || (found.from === context.pos && !context.explicit)) return null;
  return {
    from: found.from,
    options: found.entries.map((e) => ({
      label: e.label,
      type: completionType(e.kind),
      detail: e.detail,
      info: e.documentation,
    })),
    validFor: /^\w*$/,
  };
}

function completionType(kind) {
  return (
    {
      block: "class",
      key: "property",
      statement: "keyword",
      word: "keyword",
      function: "function",
      constant: "constant",
    }[kind] ?? "variable"
  );
}

function hover(editor, pos) {
  if (!language) return null;
  const found = language.hover(editor.state.doc.toString(), pos);
  if (!found) return null;
  return {
    pos: found.from,
    end: found.to,
    above: true,
    create() {
      const dom = document.createElement("div");
      dom.className = "tracer-hover";
      dom.style.maxWidth = "40em";
      dom.style.whiteSpace = "pre-wrap";
      dom.textContent = found.documentation.replace(/`/g, "");
      return { dom };
    },
  };
}

// The offset in the document of a diagnostic's 1-based line and byte column.
function offsetOf(doc, line, column) {
  if (line < 1 || line > doc.lines) return 0;
  const text = doc.line(line);
  const bytes = new TextEncoder().encode(text.text).slice(0, Math.max(column - 1, 0));
  return text.from + new TextDecoder().decode(bytes).length;
}

// Tracer's diagnostics: in the editor where they are in this text, and all of them as the command line prints them.
function showReport(report) {
  const doc = view.state.doc;
  const placed = report.diagnostics
    .filter((d) => d.path === scenePath && (d.severity === "error" || d.severity === "warning"))
    .map((d) => {
      const from = d.line > 0 ? offsetOf(doc, d.line, d.column) : 0;
      return {
        from,
        to: Math.min(from + Math.max(d.length || 1, 1), doc.length),
        severity: d.severity,
        message: d.message,
      };
    });
  view.dispatch(setDiagnostics(view.state, placed));
  diagnosticsPanel.textContent = report.text || "";
}

// The renderers: Web Workers, each with its own module, sharing each frame's bands. As many as
// the processor has cores (at most 4), or ?workers=N.
const WORKERS = Math.max(
  1,
  Math.min(
    16,
    Number(new URLSearchParams(location.search).get("workers")) || Math.min(navigator.hardwareConcurrency || 2, 4),
  ),
);
const STUCK_MS = 1000; // a worker still on an older job this long after a newer one is replaced
// Each renderer: its worker, the job it is on (0: none), when the newest job was sent to it.
const renderers = [];
const frames = new Map(); // `${job}:${final}` -> the frame being put together from its bands

// The frame a band or a share belongs to, made on its first news.
function frameOf(message) {
  const key = `${message.id}:${message.final}`;
  if (!frames.has(key)) {
    for (const older of [...frames.keys()]) if (Number(older.split(":")[0]) < message.id) frames.delete(older); // a big frame is 256 MB
    frames.set(key, { pixels: new Uint8ClampedArray(message.width * message.height * 4), bands: 0, shares: [] });
  }
  return frames.get(key);
}

function sizeCanvas(width, height) {
  if (canvas.width !== width || canvas.height !== height) {
    canvas.width = width;
    canvas.height = height;
  }
}

// A band's rows: kept in its frame; the whole image's drawn at once, a preview's when complete
// (scaled up to the whole image's size).
function onBand(message) {
  const frame = frameOf(message);
  frame.pixels.set(message.pixels, message.y * message.width * 4);
  frame.bands += 1;
  sizeCanvas(message.frame_width, message.frame_height);
  if (message.final) {
    canvas.getContext("2d").putImageData(new ImageData(message.pixels, message.width, message.rows), 0, message.y);
    painted(message.id);
    frameOf({ ...message, final: false }).overtaken = true; // its preview, if late, is not drawn over it
  } else if (frame.bands === message.bands && !frame.overtaken) {
    painted(message.id);
    const small = new OffscreenCanvas(message.width, message.height);
    small.getContext("2d").putImageData(new ImageData(frame.pixels, message.width, message.height), 0, 0);
    const context = canvas.getContext("2d");
    context.imageSmoothingEnabled = true;
    context.drawImage(small, 0, 0, canvas.width, canvas.height);
    finished(message, { milliseconds: 0, rays: 0 });
  }
  progress.value = message.final ? 0.2 + (0.8 * frame.bands) / message.bands : (0.2 * frame.bands) / message.bands;
}

// The first time a job's pixels reach the screen (its preview, or the whole image's first band
// when that comes first), recorded for the tests and benchmarks.
function painted(id) {
  if (!firstPaints.some((p) => p.id === id)) firstPaints.push({ id, at: performance.now() });
}

// A worker's share of a frame done: the frame is when every worker's is.
function onShare(message) {
  if (!message.final) return;
  const frame = frameOf(message);
  frame.shares.push(message);
  if (frame.shares.length < WORKERS) return;
  const startedAt = Math.min(...frame.shares.map((s) => s.startedAt));
  const endedAt = Math.max(...frame.shares.map((s) => s.endedAt));
  const rays = frame.shares.reduce((sum, s) => sum + s.rays, 0);
  finished(message, { milliseconds: endedAt - startedAt, rays });
}

// A frame on screen: recorded (for the tests and benchmarks), the status line and buttons set.
function finished(message, { milliseconds, rays }) {
  drawn.push({
    id: message.id,
    final: message.final,
    width: message.width,
    height: message.height,
    at: performance.now(),
    milliseconds,
  });
  canvas.dataset.version = String(Number(canvas.dataset.version) + 1);
  canvas.dataset.final = String(message.final);
  canvas.dataset.job = String(message.id);
  document.getElementById("download").disabled = !message.final;
  if (message.final) {
    progress.value = 1;
    const threads = WORKERS === 1 ? "1 worker" : `${WORKERS} workers`;
    statusLine.textContent = `${message.width}x${message.height} in ${(milliseconds / 1000).toFixed(2)} s (${(rays / 1e6).toFixed(2)} M rays, ${threads})`;
  } else {
    statusLine.textContent = `preview ${Math.round(performance.now() - editedAt)} ms after the edit; rendering…`;
  }
}

function onWorkerMessage(renderer, message) {
  if (message.id !== undefined && renderer.busy) renderer.busy = Math.max(renderer.busy, message.id);
  if (message.type === "ready") {
    if (!language) {
      language = new Language(message.language);
      fillGallery(message.scenes);
      statusLine.textContent = "ready";
    }
    return;
  }
  if (message.type === "file") return; // fetchSceneText's
  if (message.id !== undefined && message.id !== jobs) return; // an older job's news
  if (message.type === "report") {
    if (!message.report.ok && message.id === jobs) renderer.busy = 0;
    if (message.part !== 0) return;
    showReport(message.report);
    if (!message.report.ok) {
      statusLine.textContent = `${message.report.errors} error${message.report.errors === 1 ? "" : "s"}: the last good image stays`;
      progress.value = 0;
    }
  } else if (message.type === "band") {
    onBand(message);
  } else if (message.type === "share") {
    if (message.final && message.id === jobs) renderer.busy = 0;
    onShare(message);
  } else if (message.type === "failed") {
    diagnosticsPanel.textContent = `tracer stopped: ${message.message}`;
    statusLine.textContent = "the render failed: tracer restarted";
    restart(renderer); // a module that failed may be broken: a fresh one (for the next edit)
  }
}

// A fresh worker in the place of `renderer`'s (after a failure, or when stuck on a stale job).
function restart(renderer) {
  if (renderer.worker) {
    renderer.worker.terminate();
    restarts += 1;
  }
  renderer.worker = new Worker("worker.js");
  renderer.busy = 0;
  renderer.worker.onmessage = (event) => onWorkerMessage(renderer, event.data);
  renderer.worker.onerror = (event) => {
    event.preventDefault();
    diagnosticsPanel.textContent = `tracer stopped: ${event.message}`;
    restart(renderer);
  };
}

function startWorkers() {
  for (let part = 0; part < WORKERS; part++) {
    const renderer = { worker: null, busy: 0, sentAt: 0 };
    restart(renderer);
    renderers.push(renderer);
  }
}

// Sends the job to every worker, each its part.
function postJob(job) {
  renderers.forEach((renderer, part) => send(renderer, part, job));
}

function send(renderer, part, job) {
  if (!renderer.busy) renderer.busy = job.id; // idle: on it at once; busy: on it at its next band
  renderer.sentAt = performance.now();
  renderer.worker.postMessage({ ...job, part, parts: WORKERS });
}

// A worker still on an older job STUCK_MS after the newest was sent (a scene whose load or band
// runs long: the worker reads its messages only between bands) is replaced by a fresh one, which
// starts on the newest job; never one already on the newest, however long its load.
setInterval(() => {
  renderers.forEach((renderer, part) => {
    if (renderer.busy && renderer.busy < jobs && performance.now() - renderer.sentAt > STUCK_MS) {
      restart(renderer);
      send(renderer, part, lastJob);
    }
  });
}, 250);

function scheduleRender() {
  editedAt = performance.now();
  clearTimeout(renderTimer);
  renderTimer = setTimeout(() => {
    const text = view.state.doc.toString();
    lastJob = { type: "render", id: ++jobs, path: scenePath, text };
    postJob(lastJob);
    progress.value = 0;
  }, EDIT_PAUSE_MS);
}

function setText(text, path) {
  scenePath = path;
  view.dispatch({ changes: { from: 0, to: view.state.doc.length, insert: text } });
}

function fillGallery(scenes) {
  gallery.replaceChildren(
    ...scenes.map((path) => {
      const option = document.createElement("option");
      option.value = path;
      option.textContent = path.replace(/^\/scenes\//, "");
      return option;
    }),
  );
  gallery.value = scenePath;
}

gallery.addEventListener("change", async () => {
  const response = await fetchSceneText(gallery.value);
  setText(response, gallery.value);
  window.history.replaceState(null, "", location.pathname);
});

// A gallery scene's text, read from the module's file system by the worker.
function fetchSceneText(path) {
  return new Promise((resolve) => {
    const listener = (event) => {
      if (event.data.type === "file" && event.data.path === path) {
        renderers[0].worker.removeEventListener("message", listener);
        resolve(event.data.text);
      }
    };
    const { worker } = renderers[0];
    worker.addEventListener("message", listener);
    worker.postMessage({ type: "read", path });
  });
}

document.getElementById("share").addEventListener("click", async () => {
  const link = await shareLink(location.href, scenePath, view.state.doc.toString());
  window.history.replaceState(null, "", link);
  try {
    await navigator.clipboard.writeText(link);
    statusLine.textContent = "link copied";
  } catch {
    statusLine.textContent = "link in the address bar";
  }
});

document.getElementById("download").addEventListener("click", () => {
  canvas.toBlob((blob) => {
    const link = document.createElement("a");
    link.href = URL.createObjectURL(blob);
    link.download =
      scenePath
        .split("/")
        .pop()
        .replace(/\.scn$/, "") + ".png";
    link.click();
    setTimeout(() => URL.revokeObjectURL(link.href), 1000);
  }, "image/png");
});

async function begin() {
  startWorkers();
  const shared = await readShareLink(location.hash);
  if (shared) setText(shared.text, shared.path);
  else setText(await fetchSceneText(DEFAULT_SCENE), DEFAULT_SCENE);
  if ("serviceWorker" in navigator && location.protocol.startsWith("http"))
    navigator.serviceWorker.register("sw.js").catch(() => {});
}

begin();
