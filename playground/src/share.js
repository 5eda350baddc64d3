// Share links: the scene's path and text in the URL's fragment (never sent to a server), the text
// deflated and in base64url: `#in=/scenes/task2.scn&z=...`.

async function bytesThrough(stream, bytes) {
  const piped = new Blob([bytes]).stream().pipeThrough(stream);
  return new Uint8Array(await new Response(piped).arrayBuffer());
}

function toBase64Url(bytes) {
  let text = "";
  for (const byte of bytes) text += String.fromCharCode(byte);
  return btoa(text).replace(/\+/g, "-").replace(/\//g, "_").replace(/=+$/, "");
}

function fromBase64Url(text) {
  const plain = atob(text.replace(/-/g, "+").replace(/_/g, "/"));
  return Uint8Array.from(plain, (c) => c.charCodeAt(0));
}

// The link to `href` that carries `text` as the scene at `path`.
export async function shareLink(href, path, text) {
  const packed = await bytesThrough(new CompressionStream("deflate-raw"), new TextEncoder().encode(text));
  const base = href.split("#")[0];
  return `${base}#in=${encodeURIComponent(path)}&z=${toBase64Url(packed)}`;
}

// The scene a link's fragment carries ({path, text}), or null if it carries none (or a broken one).
export async function readShareLink(hash) {
  const fields = new URLSearchParams(hash.replace(/^#/, ""));
  if (!fields.get("z")) return null;
  try {
    const bytes = await bytesThrough(new DecompressionStream("deflate-raw"), fromBase64Url(fields.get("z")));
    const path = fields.get("in") || "/scenes/shared.scn";
    return { path: path.startsWith("/scenes/") ? path : "/scenes/shared.scn", text: new TextDecoder().decode(bytes) };
  } catch {
    return null;
  }
}
