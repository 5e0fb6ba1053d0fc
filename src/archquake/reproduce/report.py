"""The report of a reproduction: Markdown (figures linked) and one self-contained HTML page
(figures embedded as base64 data URIs, inline style, no scripts, no external assets)."""

from __future__ import annotations

import base64
import html
from pathlib import Path

from archquake import __version__
from archquake.validation.paper import CITATION as _PAPER

_INTRO = (
    "Every study of the paper was run again on Oppenheim's arch (t/R = 0.15, embrace 157.5 deg, R = 10 m, "
    "7 voussoirs). Each line sets a number or statement of the paper beside archquake's, with the "
    "tolerance, why that tolerance, and a mark: pass, FAIL, departs (archquake deliberately differs from "
    "the paper, explained in the note) or n/a (not computed, with the reason)."
)


def _summary(rep) -> str:
    c = rep.counts
    return (
        f"{c['pass']} pass, {c['fail']} fail, {c['departure']} departures, {c['n/a']} not applicable "
        f"({sum(c.values())} lines, {len(rep.runs)} studies, "
        f"{'quick' if rep.quick else 'full'} mode, archquake {__version__})"
    )


def md_cell(text: str) -> str:
    """``text`` as one cell of a Markdown table (pipes escaped, on one line)."""
    return str(text).replace("|", "\\|").replace("\n", " ")


def write_markdown(rep, path: Path) -> Path:
    """Write the Markdown report (figures referenced under ``figures/``)."""
    lines = [
        "# The paper regenerated: archquake beside De Lorenzis, DeJong & Ochsendorf (2007)",
        "",
        _INTRO,
        "",
        f"**Summary: {_summary(rep)}.**",
        "",
        f"Paper: {_PAPER}",
        "",
    ]
    deps = [d for r in rep.results for d in r.departures]
    if deps:
        lines += ["## Where archquake departs from the paper, and why", ""]
        lines += [f"- {d}" for d in deps] + [""]
    for run in rep.runs:
        res = run.result
        lines += [
            f"## {res.title}",
            "",
            f"Study `{res.name}`: {res.seconds:.1f} s" + (" (cached)" if run.cached else ""),
            "",
            "| quantity | source | paper | archquake | tolerance | why this tolerance | mark | note |",
            "| --- | --- | --- | --- | --- | --- | --- | --- |",
        ]
        for row in res.rows:
            lines.append(
                "| "
                + " | ".join(
                    md_cell(x)
                    for x in (
                        row.quantity,
                        row.source,
                        row.paper,
                        row.archquake,
                        row.tolerance,
                        row.justification,
                        f"**{row.mark}**",
                        row.note,
                    )
                )
                + " |"
            )
        lines.append("")
        for f in res.figures:
            lines += [f"![{f.caption}](figures/{f.file})", "", f"*{f.caption}*", ""]
    path.write_text("\n".join(lines) + "\n")
    return path


#: The style sheet of the HTML reports (the reproduction's and a bridge assessment's).
REPORT_CSS = """
body{font-family:system-ui,-apple-system,Segoe UI,Helvetica,Arial,sans-serif;max-width:1200px;margin:2em auto;
padding:0 1em;color:#222;line-height:1.4}
h1{font-size:1.5em}h2{font-size:1.2em;margin-top:2em;border-bottom:1px solid #ccc}
table{border-collapse:collapse;width:100%;font-size:0.85em;margin:0.5em 0}
th,td{border:1px solid #ccc;padding:4px 6px;vertical-align:top;text-align:left}
th{background:#f0f0f0}
tr.pass td.mark{background:#d8f0d8;color:#135e13;font-weight:bold}
tr.fail td.mark{background:#f6d0d0;color:#8a1010;font-weight:bold}
tr.departure td.mark{background:#fbe7c4;color:#7a4b00;font-weight:bold}
tr.na td.mark{background:#e4e4e4;color:#444;font-weight:bold}
figure{margin:1em 0}figure img{max-width:100%;border:1px solid #ddd}
figcaption{font-size:0.85em;color:#555}
.summary{font-size:1.05em;padding:0.6em;background:#f7f7f7;border-left:4px solid #888}
"""


def image_data_uri(path: Path) -> str:
    """The PNG at ``path`` as a ``data:`` URI, for a self-contained HTML page."""
    data = base64.b64encode(path.read_bytes()).decode("ascii")
    return f"data:image/png;base64,{data}"


def write_html(rep, path: Path) -> Path:
    """Write the self-contained HTML report."""
    e = html.escape
    figures = Path(rep.out) / "figures"
    parts = [
        "<!DOCTYPE html>",
        '<html lang="en"><head><meta charset="utf-8">',
        "<title>archquake: the paper regenerated</title>",
        f"<style>{REPORT_CSS}</style></head><body>",
        "<h1>The paper regenerated: archquake beside De Lorenzis, DeJong &amp; Ochsendorf (2007)</h1>",
        f"<p>{e(_INTRO)}</p>",
        f'<p class="summary" id="summary">Summary: {e(_summary(rep))}.</p>',
        f"<p>Paper: {e(_PAPER)}</p>",
    ]
    deps = [d for r in rep.results for d in r.departures]
    if deps:
        parts.append('<h2 id="departures">Where archquake departs from the paper, and why</h2><ul>')
        parts += [f"<li>{e(d)}</li>" for d in deps]
        parts.append("</ul>")
    for run in rep.runs:
        res = run.result
        parts.append(f'<h2 id="{e(res.name)}">{e(res.title)}</h2>')
        parts.append(
            f"<p>Study <code>{e(res.name)}</code>: {res.seconds:.1f} s"
            + (" (cached)" if run.cached else "")
            + "</p>"
        )
        parts.append(
            '<table class="checks"><thead><tr><th>quantity</th><th>source</th><th>paper</th>'
            "<th>archquake</th><th>tolerance</th><th>why this tolerance</th><th>mark</th>"
            "<th>note</th></tr></thead><tbody>"
        )
        for row in res.rows:
            cls = {"pass": "pass", "fail": "fail", "departure": "departure", "n/a": "na"}[row.status]
            cells = "".join(
                f"<td>{e(str(x))}</td>"
                for x in (
                    row.quantity,
                    row.source,
                    row.paper,
                    row.archquake,
                    row.tolerance,
                    row.justification,
                )
            )
            parts.append(
                f'<tr class="row {cls}" data-study="{e(res.name)}">{cells}'
                f'<td class="mark">{e(row.mark)}</td><td>{e(row.note)}</td></tr>'
            )
        parts.append("</tbody></table>")
        for f in res.figures:
            parts.append(
                f'<figure><img alt="{e(f.caption)}" src="{image_data_uri(figures / f.file)}">'
                f"<figcaption>{e(f.caption)}</figcaption></figure>"
            )
    parts.append("</body></html>")
    path.write_text("\n".join(parts) + "\n")
    return path


__all__ = ["REPORT_CSS", "image_data_uri", "md_cell", "write_html", "write_markdown"]
