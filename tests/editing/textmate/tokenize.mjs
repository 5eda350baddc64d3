// Tokenizes files with a TextMate grammar as VS Code does (vscode-textmate on Oniguruma) and
// prints, for each file, its tokens as JSON: [{file, tokens: [[line, column, text, scopes]]}].
// Usage: node tokenize.mjs GRAMMAR.json FILE...
import { readFileSync } from "node:fs";
import { createRequire } from "node:module";

const require = createRequire(import.meta.url);
const oniguruma = require("vscode-oniguruma");
const textmate = require("vscode-textmate");

const [grammarPath, ...files] = process.argv.slice(2);
const wasm = readFileSync(require.resolve("vscode-oniguruma/release/onig.wasm")).buffer;
await oniguruma.loadWASM(wasm);
const registry = new textmate.Registry({
  onigLib: Promise.resolve({
    createOnigScanner: (patterns) => new oniguruma.OnigScanner(patterns),
    createOnigString: (text) => new oniguruma.OnigString(text),
  }),
  loadGrammar: async () => textmate.parseRawGrammar(readFileSync(grammarPath, "utf8"), grammarPath),
});
const grammar = await registry.loadGrammar("source.tracer");
const out = [];
for (const file of files) {
  const lines = readFileSync(file, "utf8").split("\n");
  let state = textmate.INITIAL;
  const tokens = [];
  lines.forEach((line, index) => {
    const result = grammar.tokenizeLine(line, state);
    for (const token of result.tokens)
      tokens.push([index + 1, token.startIndex + 1, line.slice(token.startIndex, token.endIndex), token.scopes]);
    state = result.ruleStack;
  });
  out.push({ file, tokens });
}
process.stdout.write(JSON.stringify(out));
