// LinuxCNC-dialect G-code highlighting for CodeMirror 6 (a StreamLanguage): comments in
// parentheses and after ';', G/M words, axis and other words, O-word statements, parameters
// (#5, #<name>, #<_global>), expressions in brackets, numbers.
import { StreamLanguage } from "@codemirror/language";

const oWords = /^(sub|endsub|call|return|if|elseif|else|endif|while|endwhile|do|repeat|endrepeat|break|continue)\b/i;

export const gcodeLanguage = StreamLanguage.define({
  name: "gcode",
  startState: () => ({}),
  token(stream) {
    if (stream.eatSpace()) return null;
    if (stream.match(/^\(.*?\)/) || stream.match(/^;.*/)) return "comment";
    if (stream.match(/^[oO](<[^>]*>|\d+)/)) {
      stream.eatSpace();
      stream.match(oWords);
      return "keyword";
    }
    if (stream.match(/^#<[^>]*>/) || stream.match(/^#\d+/)) return "variableName";
    if (stream.match(/^[gGmM]\s*\d+(\.\d+)?/)) return "keyword";
    if (stream.match(/^[xXyYzZaAbBcCuUvVwW]/)) return "propertyName";
    if (stream.match(/^[fFsStTpPqQrRiIjJkKhHdDlLnN]/)) return "attributeName";
    if (stream.match(/^[+-]?(\d+\.?\d*|\.\d+)/)) return "number";
    if (stream.match(/^(and|or|xor|mod|eq|ne|gt|ge|lt|le|sin|cos|tan|asin|acos|atan|abs|sqrt|exp|ln|round|fix|fup|exists)\b/i))
      return "operator";
    stream.next();
    return null;
  },
});
