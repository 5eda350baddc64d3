// The scene language for the editor, from tracer's own tables (the module's language(), the same
// JSON as `tracer --language-json`, which the language server and the TextMate grammar are made
// from): completion and hover as the language server gives them (tools/tracer_tools/editing/
// language.py, lsp.py and scene_text.py), and highlighting by the committed TextMate grammar's
// patterns (grammar/vscode/syntaxes/tracer.tmLanguage.json).
import { StreamLanguage } from "@codemirror/language";
import { tags } from "@lezer/highlight";
import grammar from "../../grammar/vscode/syntaxes/tracer.tmLanguage.json";

// One thing the editor can complete and explain: label, kind, one-line detail, Markdown text.
function entry(label, kind, detail, documentation) {
  return { label, kind, detail, documentation };
}

// The tables turned into entries: blocks, keys, statements, words, constants, functions.
export class Language {
  constructor(tables) {
    this.blocks = new Map(tables.blocks.map((block) => [block.kind, block]));
    this.topLevel = tables.blocks.filter((block) => block.top_level).map((block) => block.kind);
    this.patterns = tables.blocks.filter((block) => block.pattern).map((block) => block.kind);
    this.words = new Map();
    for (const statement of tables.statements) {
      if (!statement.keyword) continue;
      const previous = this.words.get(statement.keyword);
      const text = `\`${statement.syntax}\`: ${statement.meaning}`;
      this.words.set(
        statement.keyword,
        entry(
          statement.keyword,
          "statement",
          statement.syntax,
          previous ? `${previous.documentation}\n\n${text}` : text,
        ),
      );
    }
    for (const word of tables.words)
      if (!this.words.has(word.word)) this.words.set(word.word, entry(word.word, "word", word.word, word.meaning));
    for (const constant of tables.constants)
      this.words.set(
        constant.name,
        entry(constant.name, "constant", constant.meaning, `\`${constant.name}\`: ${constant.meaning}`),
      );
    for (const fn of tables.functions) {
      const signature = `${fn.name}(${"abcdefgh".slice(0, fn.arity).split("").join(", ")})`;
      this.words.set(fn.name, entry(fn.name, "function", signature, `\`${signature}\`: ${fn.meaning}`));
    }
  }

  blockEntry(kind) {
    const block = this.blocks.get(kind);
    const keys = block.keys.map((key) => `- \`${key.name}\`: ${key.meaning}`).join("\n");
    return entry(
      kind,
      "block",
      block.summary,
      `\`${kind}${block.named ? " NAME" : ""} { ... }\`: ${block.summary}\n\n${keys}`,
    );
  }

  keyEntry(kind, name) {
    const key = (this.blocks.get(kind)?.keys ?? []).find((k) => k.name === name);
    if (!key) return null;
    const fallback = key.default === null ? "required" : `default \`${key.default}\``;
    return entry(
      name,
      "key",
      `${key.type} (${fallback})`,
      `\`${kind}.${name}\`: ${key.meaning}\n\n${key.type}; ${fallback}; allowed: ${key.allowed}`,
    );
  }

  keyTakesPattern(kind, name) {
    return (this.blocks.get(kind)?.keys ?? []).some((key) => key.name === name && key.type.includes("pattern"));
  }

  // The block kind whose braces hold `offset` (null at the top level or in statements' braces).
  contextKind(text, offset) {
    const braces = openBraces(text, offset);
    if (!braces.length) return null;
    const words = braces[braces.length - 1].words;
    const last = words[words.length - 1];
    if (this.blocks.has(last)) return last;
    if (words.length >= 2 && this.blocks.has(words[words.length - 2]) && /^[A-Za-z_]\w*$/.test(last))
      return words[words.length - 2]; // a named block
    return null;
  }

  // What the word at `offset` is: a key of the enclosing block, a block kind or a built-in.
  hover(text, offset) {
    const found = wordAt(text, offset);
    if (!found) return null;
    const kind = this.contextKind(text, found.start);
    const key = kind && this.keyEntry(kind, found.word);
    if (key) return { ...key, from: found.start, to: found.start + found.word.length };
    const known = this.blocks.has(found.word) ? this.blockEntry(found.word) : this.words.get(found.word);
    return known ? { ...known, from: found.start, to: found.start + found.word.length } : null;
  }

  // What may be written at `offset`: keys in a block (and patterns after a key that takes one),
  // else blocks and statements; built-ins everywhere. Those starting with the word typed.
  completions(text, offset) {
    const kind = this.contextKind(text, offset);
    const typed = wordBefore(text, offset);
    let entries = [];
    if (kind) {
      entries = (this.blocks.get(kind)?.keys ?? []).map((key) => this.keyEntry(kind, key.name));
      const before = wordsBefore(text, offset - typed.length, 1);
      if (before.length && this.keyTakesPattern(kind, before[0]))
        entries.push(...this.patterns.map((k) => this.blockEntry(k)));
    } else {
      entries = this.topLevel.map((k) => this.blockEntry(k));
      entries.push(...[...this.words.values()].filter((e) => e.kind === "statement"));
    }
    entries.push(...[...this.words.values()].filter((e) => ["function", "constant", "word"].includes(e.kind)));
    return { from: offset - typed.length, entries: entries.filter((e) => e.label.startsWith(typed)) };
  }
}

// A comment, a string (to its closing quote or the end of its line) or a brace.
const BRACE_OR_SKIPPED = /#[^\n]*|"[^"\n]*"?|[{}]/g;

function wordsBefore(text, offset, most = 3) {
  const found = text.slice(Math.max(0, offset - 200), offset).match(/[A-Za-z_][A-Za-z0-9_]*|\)|\.\.|[0-9.]+/g) ?? [];
  return found.slice(-most);
}

// The braces still open at `offset`, outermost first, each with the words just before it.
function openBraces(text, offset) {
  const stack = [];
  BRACE_OR_SKIPPED.lastIndex = 0;
  for (let match; (match = BRACE_OR_SKIPPED.exec(text)) && match.index < offset;) {
    if (match[0] === "{") stack.push({ offset: match.index, words: wordsBefore(text, match.index) });
    else if (match[0] === "}") stack.pop();
  }
  return stack;
}

function wordAt(text, offset) {
  const pattern = /[A-Za-z_][A-Za-z0-9_]*/g;
  const start = Math.max(0, offset - 100);
  pattern.lastIndex = start;
  for (let match; (match = pattern.exec(text)) && match.index <= offset;)
    if (match.index + match[0].length >= offset) return { word: match[0], start: match.index };
  return null;
}

function wordBefore(text, offset) {
  let start = offset;
  while (start > 0 && offset - start < 100 && /\w/.test(text[start - 1])) start--;
  const typed = text.slice(start, offset);
  return /^[A-Za-z_]\w*$/.test(typed) ? typed : "";
}

// The TextMate scopes' highlighting tags: the first scope name part that says what a token is.
const TAG_OF_SCOPE = [
  ["comment", tags.lineComment],
  ["invalid", tags.invalid],
  ["string", tags.string],
  ["constant.numeric", tags.number],
  ["keyword.control", tags.controlKeyword],
  ["keyword.operator.word", tags.operatorKeyword],
  ["keyword.operator", tags.operator],
  ["constant.language.choice", tags.atom],
  ["constant.language", tags.bool],
  ["entity.name.type", tags.typeName],
  ["variable.other.property", tags.propertyName],
  ["support.function", tags.function(tags.variableName)],
  ["support.constant", tags.constant(tags.variableName)],
  ["variable", tags.variableName],
  ["punctuation", tags.punctuation],
];

// The grammar's patterns, in its order, each anchored where the stream stands.
const RULES = grammar.patterns.map((pattern) => {
  const scope = pattern.name;
  const tokenName = scope.replace(/\.tracer$/, "").replace(/\./g, "-");
  return {
    regex: new RegExp(pattern.match.replace(/\$$/, "(?=\\n|$)"), "y"),
    tokenName,
    tag: (TAG_OF_SCOPE.find(([prefix]) => scope.startsWith(prefix)) ?? [null, tags.content])[1],
  };
});

// Highlighting by the TextMate grammar: at each place, the first pattern that matches there.
export const sceneLanguage = StreamLanguage.define({
  name: "tracer",
  token(stream) {
    if (stream.eatSpace()) return null;
    const line = stream.string;
    for (const rule of RULES) {
      rule.regex.lastIndex = stream.pos;
      const match = rule.regex.exec(line);
      if (match && match[0].length > 0) {
        stream.pos += match[0].length;
        return rule.tokenName;
      }
    }
    stream.next();
    return null;
  },
  tokenTable: Object.fromEntries(RULES.map((rule) => [rule.tokenName, rule.tag])),
  languageData: { commentTokens: { line: "#" } },
});
