// The paper's LaTeX, rendered locally with KaTeX (static/vendor/katex).
// Cells of the tables are text-mode LaTeX with $...$ math inside \parbox; most claims are
// math. The paper's own macros are defined here.
"use strict";

export const MACROS = {
  "\\bM": "\\boldsymbol{M}",
  "\\bK": "\\boldsymbol{K}",
  "\\bS": "\\boldsymbol{S}",
  "\\br": "\\boldsymbol{r}",
  "\\ba": "\\boldsymbol{a}",
  "\\bv": "\\boldsymbol{v}",
  "\\bs": "\\boldsymbol",
  "\\gam": "\\gamma",
  "\\om": "\\omega",
  "\\ta": "\\theta",
  "\\vfi": "\\varphi",
  "\\eps": "\\varepsilon",
  "\\dl": "\\delta",
  "\\fracs": "\\tfrac",
  "\\const": "\\mathrm{const}",
  "\\arr": "\\begin{array}{c}#1\\end{array}",
  "\\ctg": "\\operatorname{ctg}",
  "\\arctg": "\\operatorname{arctg}",
  "\\tr": "\\operatorname{tr}",
  "\\grad": "\\operatorname{grad}",
  "\\pt": "\\frac{\\partial #1}{\\partial #2}",
  "\\q": "\\quad",
  "\\qq": "\\qquad",
  "\\x": "\\times",
  "\\wh": "\\widehat",
  "\\wt": "\\widetilde",
  "\\ol": "\\overline",
  "\\eqref": "\\text{(#1)}",
  "\\ref": "\\text{#1}",
};

const katexOptions = (display) => ({
  displayMode: display,
  throwOnError: true,
  strict: "ignore",
  trust: false,
  macros: { ...MACROS },
  output: "htmlAndMathml", // MathML for screen readers
});

function escapeHtml(s) {
  return s.replace(/[&<>"']/g, (c) => ({ "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;", "'": "&#39;" })[c]);
}

export function mathHtml(tex, display = false) {
  let src = tex.trim().replace(/(\\\\\s*)+$/, ""); // a trailing line break prints nothing
  if (/(^|[^\\])&/.test(src) && !/\\begin\{/.test(src)) {
    src = `\\begin{aligned}${src}\\end{aligned}`;
  }
  try {
    return window.katex.renderToString(src, katexOptions(display));
  } catch (err) {
    return `<code class="tex-fallback" title="${escapeHtml(String(err.message || err))}">${escapeHtml(tex)}</code>`;
  }
}

// Text-mode LaTeX (a table cell, a sentence with $...$): text commands become HTML,
// math segments go to KaTeX.
export function textHtml(src, { bigFractions = true } = {}) {
  const out = [];
  let i = 0;
  let text = "";
  const flush = () => {
    if (text) out.push(textCommands(text));
    text = "";
  };
  while (i < src.length) {
    const c = src[i];
    if (c === "\\" && (src[i + 1] === "$")) {
      text += "$";
      i += 2;
    } else if (c === "$") {
      const dbl = src[i + 1] === "$";
      const close = src.indexOf(dbl ? "$$" : "$", i + (dbl ? 2 : 1));
      if (close < 0) {
        text += src.slice(i);
        break;
      }
      flush();
      let tex = src.slice(i + (dbl ? 2 : 1), close);
      // a printed \frac inside a narrow cell is unreadable at text size
      if (bigFractions && /\\frac(?![a-z])/.test(tex)) tex = `\\displaystyle ${tex}`;
      out.push(mathHtml(tex, dbl));
      i = close + (dbl ? 2 : 1);
    } else {
      text += c;
      i += 1;
    }
  }
  flush();
  return out.join("");
}

const ACCENTS = { "'": "\u0301", "`": "\u0300", '"': "\u0308", "^": "\u0302", "~": "\u0303" };

function textCommands(s) {
  let h = escapeHtml(s);
  h = h.replace(/\\\\(\[[^\]]*\])?\s*/g, "<br>");
  h = h.replace(/\\(newline|par)\b\s*/g, "<br>");
  h = h.replace(/\\(centering|raggedright|raggedleft|noindent|medskip|smallskip|bigskip|hfill|small|footnotesize)\b\s*/g, "");
  h = h.replace(/\\(emph|em|textit)\{([^{}]*)\}/g, "<em>$2</em>");
  h = h.replace(/\{\\em\s+([^{}]*)\}/g, "<em>$1</em>");
  h = h.replace(/\\textbf\{([^{}]*)\}/g, "<strong>$1</strong>");
  h = h.replace(/\\eqref\s*\{([^{}]*)\}/g, '<span class="eqref">($1)</span>');
  h = h.replace(/\\ref\s*\{([^{}]*)\}/g, '<span class="eqref">$1</span>');
  h = h.replace(/\\cite\{([^{}]*)\}/g, '<span class="cite">[$1]</span>');
  h = h.replace(/\\([`'"^~])\{?([A-Za-z])\}?/g, (m, a, ch) => (ch + ACCENTS[a]).normalize("NFC"));
  h = h.replace(/\\No\b/g, "№");
  h = h.replace(/\\[,;:]/g, "\u2009").replace(/\\ /g, " ").replace(/~/g, "\u00a0");
  h = h.replace(/---/g, "\u2014").replace(/--/g, "\u2013");
  h = h.replace(/\\(one)\b/g, "$1");
  h = h.replace(/\\[A-Za-z]+\*?/g, "").replace(/[{}]/g, "");
  return h;
}

// A printed statement without $...$ that is words, not a formula: three words in a row, or
// one word of four letters outside braces and commands ("unknown", "S. A. Chaplygin (1897)").
// The same rule as catalogue/symbols.py is_prose, which reads the symbols the page shows.
export function isProse(src) {
  const words = src.replace(/\\[A-Za-z]+/g, " ").replace(/\{[^{}]*\}/g, " ");
  return /\b[a-z]{3,}\s+[a-z]{2,}\s+[a-z]{3,}\b/.test(words) || /(^|[^A-Za-z])[A-Za-z]{4,}/.test(words);
}

// A claim's `printed`: text with $...$, or a display formula.
export function printedHtml(src) {
  if (src.includes("$")) return textHtml(src);
  if (isProse(src)) return textHtml(src);
  return mathHtml(src, true);
}

export { escapeHtml };
