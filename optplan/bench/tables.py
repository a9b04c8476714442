"""Tables rendered as markdown (for terminals and READMEs) or LaTeX (booktabs, for papers)."""
from __future__ import annotations

import re
from dataclasses import dataclass, field

FORMATS = ("markdown", "latex")

_LATEX_ESCAPES = {"\\": r"\textbackslash{}", "&": r"\&", "%": r"\%", "$": r"\$", "#": r"\#", "_": r"\_",
                  "{": r"\{", "}": r"\}", "~": r"\textasciitilde{}", "^": r"\textasciicircum{}"}
_NUMBER = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")


def latex_escape(text: str) -> str:
    """``text`` with LaTeX's special characters escaped."""
    return "".join(_LATEX_ESCAPES.get(ch, ch) for ch in str(text))


@dataclass
class Table:
    """Rows of already formatted cells; ``notes`` are lines printed after the table."""

    header: list[str]
    rows: list[list[str]] = field(default_factory=list)
    caption: str = ""
    notes: list[str] = field(default_factory=list)

    def markdown(self) -> str:
        lines = ["| " + " | ".join(self.header) + " |", "|" + "---|" * len(self.header)]
        lines += ["| " + " | ".join(map(str, r)) + " |" for r in self.rows]
        if self.notes:
            lines.append("")
            lines += self.notes
        return "\n".join(lines)

    def latex(self) -> str:
        """A ``table`` environment with a booktabs ``tabular`` (needs ``\\usepackage{booktabs}``);
        numeric columns are right-aligned."""
        def numeric(j: int) -> bool:
            cells = [str(r[j]) for r in self.rows if j < len(r) and str(r[j]) not in ("-", "")]
            return bool(cells) and all(_NUMBER.match(c.split(" ")[0]) for c in cells)

        align = "".join("r" if numeric(j) else "l" for j in range(len(self.header)))
        out = [r"\begin{table}[ht]", r"\centering"]
        if self.caption:
            out.append(rf"\caption{{{latex_escape(self.caption)}}}")
        out += [rf"\begin{{tabular}}{{{align}}}", r"\toprule",
                " & ".join(latex_escape(h) for h in self.header) + r" \\", r"\midrule"]
        out += [" & ".join(latex_escape(c) for c in r) + r" \\" for r in self.rows]
        out += [r"\bottomrule", r"\end{tabular}"]
        if self.notes:
            out.append(r"\par\smallskip{\footnotesize " + latex_escape(" ".join(n for n in self.notes if n))
                       + "}")
        out.append(r"\end{table}")
        return "\n".join(out)

    def render(self, fmt: str = "markdown") -> str:
        if fmt not in FORMATS:
            from ..errors import ParameterError

            raise ParameterError(f"table format must be one of {', '.join(FORMATS)}, got {fmt!r}")
        return self.markdown() if fmt == "markdown" else self.latex()
