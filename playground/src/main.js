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
let editedAt = 0; // when the job's edit was made (for the edit-to-preview time)
let renderTimer = 0;
let worker = null;
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
      keymap.of([...closeBracketsKeymap, ...defaultKeymap, ...searchKeymap, ...historyKeymap, ...completionKeymap, indentWithTab]),
      EditorView.updateListener.of((update) => {
        if (update.docChanged) scheduleRender();
      }),
    ],
  }),
});

// What the page drew (job id, final or preview, size), and the editor: for the browser tests.
const drawn = [];
window.tracerPlayground = { view, drawn, jobs: () => jobs, jobText: () => lastJob && lastJob.text };

function complete(context) {
  if (!language) return null;
  const found = language.completions(context.state.doc.toString(), context.pos);
  if (!found.entries.length || (found.from === context.pos && !context.explicit)) return null;
  return {
    from: found.from,
    options: found.entries.map((e) => ({ label: e.label, type: completionType(e.kind), detail: e.detail, info: e.documentation })),
    validFor: /^\w*$/,
  };
}

function completionType(kind) {
  return { block: "class", key: "property", statement: "keyword", word: "keyword", function: "function", constant: "constant" }[kind] ?? "variable";
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
      return { from, to: Math.min(from + Math.max(d.length || 1, 1), doc.length), severity: d.severity, message: d.message };
    });
  view.dispatch(setDiagnostics(view.state, placed));
  diagnosticsPanel.textContent = report.text || "";
}

// Draws a frame's pixels: a preview scaled up to the frame's size, the whole image as it is.
function drawImage(message) {
  const image = new ImageData(message.pixels, message.width, message.height);
  if (message.final) {
    canvas.width = message.width;
    canvas.height = message.height;
    canvas.getContext("2d").putImageData(image, 0, 0);
  } else {
    const small = new OffscreenCanvas(message.width, message.height);
    small.getContext("2d").putImageData(image, 0, 0);
    const context = canvas.getContext("2d");
    context.imageSmoothingEnabled = true;
    context.drawImage(small, 0, 0, canvas.width, canvas.height);
  }
  drawn.push({ id: message.id, final: message.final, width: message.width, height: message.height });
  canvas.dataset.version = String(Number(canvas.dataset.version) + 1);
  canvas.dataset.final = String(message.final);
  canvas.dataset.job = String(message.id);
}

function onWorkerMessage(event) {
  const message = event.data;
  if (message.type === "ready") {
    language = new Language(message.language);
    fillGallery(message.scenes);
    statusLine.textContent = "ready";
    if (lastJob) worker.postMessage(lastJob);
    return;
  }
  if (message.id !== undefined && message.id !== jobs) return; // an older job's news
  if (message.type === "report") {
    showReport(message.report);
    if (!message.report.ok) {
      statusLine.textContent = `${message.report.errors} error${message.report.errors === 1 ? "" : "s"}: the last good image stays`;
      progress.value = 0;
    }
  } else if (message.type === "progress") {
    progress.value = message.final ? 0.25 + 0.75 * message.fraction : 0.25 * message.fraction;
  } else if (message.type === "image") {
    if (message.final) {
      canvas.width = message.width;
      canvas.height = message.height;
    } else if (canvas.dataset.size !== `${message.width * 4}x${message.height * 4}`) {
      canvas.width = message.width * 4; // the preview is a quarter of the frame
      canvas.height = message.height * 4;
    }
    drawImage(message);
    canvas.dataset.size = `${canvas.width}x${canvas.height}`;
    const seconds = (message.milliseconds / 1000).toFixed(2);
    statusLine.textContent = message.final
      ? `${message.width}x${message.height} in ${seconds} s (${(message.rays / 1e6).toFixed(2)} M rays)`
      : `preview ${Math.round(performance.now() - editedAt)} ms after the edit; rendering ${canvas.width}x${canvas.height}…`;
    if (!message.final) canvas.dataset.previewMs = String(Math.round(performance.now() - editedAt));
    document.getElementById("download").disabled = !message.final;
    if (message.final) progress.value = 1;
  } else if (message.type === "failed") {
    diagnosticsPanel.textContent = `tracer stopped: ${message.message}`;
    statusLine.textContent = "the render failed: tracer restarted";
    startWorker(); // a module that failed may be broken: a fresh one
  }
}

function startWorker() {
  if (worker) worker.terminate();
  worker = new Worker("worker.js");
  worker.onmessage = onWorkerMessage;
  worker.onerror = (event) => {
    event.preventDefault();
    diagnosticsPanel.textContent = `tracer stopped: ${event.message}`;
    startWorker();
  };
}

function scheduleRender() {
  editedAt = editedAt || performance.now();
  clearTimeout(renderTimer);
  renderTimer = setTimeout(() => {
    const text = view.state.doc.toString();
    lastJob = { type: "render", id: ++jobs, path: scenePath, text };
    worker.postMessage(lastJob);
    editedAt = performance.now() - EDIT_PAUSE_MS;
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
        worker.removeEventListener("message", listener);
        resolve(event.data.text);
      }
    };
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
    link.download = scenePath.split("/").pop().replace(/\.scn$/, "") + ".png";
    link.click();
    setTimeout(() => URL.revokeObjectURL(link.href), 1000);
  }, "image/png");
});

async function begin() {
  startWorker();
  const shared = await readShareLink(location.hash);
  if (shared) setText(shared.text, shared.path);
  else setText(await fetchSceneText(DEFAULT_SCENE), DEFAULT_SCENE);
  if ("serviceWorker" in navigator && location.protocol.startsWith("http"))
    navigator.serviceWorker.register("sw.js").catch(() => {});
}

begin();
