"""index.html of a bench folder: the run's provenance and noise, every chart (or why it was not
drawn) with its fitted laws and flagged configurations, the laws and the cost model as tables,
the images and the CSV as a table."""

import html
import os
import urllib.parse

from bench_data import flagged_rows, fmt, median, number

STYLE = """body { font-family: sans-serif; margin: 1.5em; max-width: 1400px; }
figure { display: inline-block; margin: 0.6em; vertical-align: top; } .skipped { color: #a33; }
figure img { max-width: 100%; border: 1px solid #ccc; } figcaption { max-width: 60em; }
table { border-collapse: collapse; font-size: 0.75em; } th { background: #eee; }
th, td { border: 1px solid #bbb; padding: 2px 5px; text-align: right; }
td:first-child, th:first-child { text-align: left; } .flagged { color: #a33; }
table.facts td { text-align: left; }"""
e = html.escape


def href(path):
    """A relative URL for an attribute: percent-encoded, then HTML-escaped."""
    return html.escape(urllib.parse.quote(path), quote=True)


def list_images(out_dir):
    """Sorted file names of DIR/images/*.png (empty when the folder is absent)."""
    folder = os.path.join(out_dir, "images")
    names = os.listdir(folder) if os.path.isdir(folder) else []
    return sorted(f for f in names
                  if f.lower().endswith(".png") and os.path.isfile(os.path.join(folder, f)))


def flatten(value, prefix=""):
    """[(dotted key, text)] of a JSON value: nested objects' keys joined by dots, lists joined
    by commas, in the document's order."""
    if isinstance(value, dict):
        out = []
        for k, v in value.items():
            out += flatten(v, f"{prefix}.{k}" if prefix else str(k))
        return out
    if isinstance(value, list):
        return [(prefix, ", ".join(str(v) for v in value))]
    return [(prefix, "" if value is None else str(value))]


def facts_table(pairs):
    """A two-column table of (key, text) pairs."""
    out = ['<table class="facts">']
    out += [f"<tr><th>{e(k)}</th><td>{e(v)}</td></tr>" for k, v in pairs]
    return out + ["</table>"]


def provenance_section(document):
    """Where the numbers come from: results.json's provenance (device, driver, CPU, commit,
    command line, date, scene), or its older device, scene and size keys."""
    out = ["<h2>Provenance</h2>"]
    provenance = document.get("provenance")
    if isinstance(provenance, dict) and provenance:
        return out + facts_table(flatten(provenance))
    older = [(k, document[k]) for k in ("device", "scene", "size", "quick") if k in document]
    if older:
        return out + ['<p class="skipped">results.json has no provenance (an older bench); '
                      "what it says:</p>"] + facts_table(flatten(dict(older)))
    return out + ['<p class="skipped">No provenance: results.json is absent or has none.</p>']


def noise_section(document, rows, limit):
    """The run's noise figure: median coefficient of variation of the whole frame, the flag
    limit, how many configurations are flagged, and which."""
    noise = document.get("noise") if isinstance(document.get("noise"), dict) else {}
    cvs = [number(r, "total_cv") for r in rows if number(r, "total_cv") is not None]
    median_cv = noise.get("median_cv", median(cvs) if cvs else None)
    flagged = flagged_rows(rows)
    out = ["<h2>Noise</h2>", f"<p>Median coefficient of variation of the whole frame over the "
           f"rounds: <b>{e(fmt(median_cv) if isinstance(median_cv, (int, float)) else 'unknown')}"
           f"</b>; a configuration is flagged when its interquartile range exceeds "
           f"<b>{e(fmt(limit))}</b> x its median; <b>{len(flagged)}</b> flagged"]
    if isinstance(noise.get("flagged"), int) and noise["flagged"] != len(flagged):
        out[-1] += f" (results.json says {noise['flagged']})"
    for key in ("rounds", "best_of", "seed"):
        if key in noise:
            out[-1] += f"; {key} {e(str(noise[key]))}"
    if isinstance(noise.get("frame_median_cv"), (int, float)):
        out[-1] += (f"; frame to frame (every single timed frame) "
                    f"{e(fmt(noise['frame_median_cv']))}")
    out[-1] += ".</p>"
    if flagged:
        out += ['<ul class="flagged">'] + [
            f"<li>{e(r.get('config', ''))}: total {e(r.get('total_ms', ''))} ms, interquartile "
            f"range {e(r.get('total_iqr_ms', ''))} ms{': ' if r.get('flag_reason') else ''}"
            f"{e(r.get('flag_reason', ''))}</li>" for r in flagged] + ["</ul>"]
    return out


def laws_section(laws):
    """Every fitted log-log slope, a row each."""
    out = ["<h2>Fitted laws</h2>", '<p>Least-squares slope of log(median GPU ms) on log(x) per '
           'series, line and pass, over x &gt; 0 and time &gt; 0, flagged rows left out (also '
           'in <a href="laws.json">laws.json</a>).</p>']
    if not laws:
        return out + ['<p class="skipped">No sweep had times at two or more values.</p>']
    out += ["<table>", "<tr><th>series</th><th>line</th><th>pass</th><th>law</th>"
            "<th>slope</th><th>points</th></tr>"]
    out += [f"<tr><td>{e(w['series'])}</td><td>{e(w['line'])}</td><td>{e(w['pass'])}</td>"
            f"<td>{e(w['law'])}</td><td>{w['slope']:.2f}</td><td>{w['points']}</td></tr>"
            for w in laws]
    return out + ["</table>"]


def cost_section(model):
    """The cost model: per pass (and per method where it depends on it) the unit costs."""
    out = ["<h2>Cost model</h2>", "<p>Each pass's median GPU time fitted, by non-negative least "
           "squares over every unflagged row, as a sum of unit costs times the counters that "
           "drive it (also in <a href=\"cost_model.json\">cost_model.json</a>). The counters "
           "are the same on any device: multiply another run's counters by these costs to "
           "predict its frame on this device, or this run's counters by another device's costs."
           "</p>"]
    fits = model["passes"]
    if not fits:
        return out + ['<p class="skipped">No pass had times and counters to fit.</p>']
    out += ["<table>", "<tr><th>pass</th><th>rows</th><th>R²</th><th>term</th><th>counter</th>"
            "<th>cost</th><th>unit</th></tr>"]
    for f in fits:
        what = f["pass"] + (f" ({f['method']})" if f.get("method") else "")
        for k, t in enumerate(f["terms"] or [{"term": "", "counter": "", "ns": None, "unit": ""}]):
            lead = (f"<td>{e(what)}</td><td>{f['rows']}</td><td>{f['r2']:.3f}</td>" if k == 0
                    else "<td></td><td></td><td></td>")
            out.append(f"<tr>{lead}<td>{e(t['term'])}</td><td>{e(t['counter'])}</td>"
                       f"<td>{e(fmt(t['ns']))}</td><td>{e(t['unit'])}</td></tr>")
        left_out = f["not_in_data"] + f["zero_in_every_row"]
        if left_out:
            out.append(f'<tr><td></td><td colspan="6" class="skipped">not fitted (no data or 0 '
                       f"in every row): {e(', '.join(left_out))}</td></tr>")
    out.append("</table>")
    total = model["total"]
    if total.get("rows"):
        out.append(f"<p>The sum of the fitted passes against the whole frame over {total['rows']}"
                   f" rows: R² {total['r2']:.3f}, median relative error "
                   f"{fmt(total.get('median_relative_error'), 3)}.</p>")
    return out


def chart_section(chart):
    """A chart's figure, its caption, its laws and the configurations it draws hollow."""
    name, title = chart["name"], chart["title"]
    if chart["skipped"]:
        return [f'<p class="skipped"><b>{e(title)}</b>: not drawn: {e(chart["skipped"])}.</p>']
    out = [f'<figure id="{e(name)}"><img src="{href("charts/" + name + ".png")}" '
           f'alt="{e(title)}">',
           f"<figcaption><b>{e(title)}</b>. {e(chart['caption'])} "
           f'(<a href="{href("charts/" + name + ".svg")}">SVG</a>)']
    if chart["laws"]:
        out.append("<br>Laws: " + "; ".join(e(f"{w['line']}: {w['law']}") for w in chart["laws"]))
    if chart.get("crossovers"):
        out.append("<br>Crossings (the black crosses): " + "; ".join(e(c["text"]) for c in chart["crossovers"]))
    if chart["flagged"]:
        out.append('<br><span class="flagged">Flagged (drawn hollow, spread over the limit): '
                   + ", ".join(e(c) for c in chart["flagged"]) + "</span>")
    return out + ["</figcaption></figure>"]


def render_index(header, rows, charts, images, notes, document, limit, laws, model):
    """The text of index.html."""
    out = ["<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
           "<title>punctual bench results</title>", f"<style>\n{STYLE}\n</style></head><body>",
           "<h1>punctual bench results</h1>",
           f"<p>{len(rows)} configurations from <a href=\"results.csv\">results.csv</a>. "
           "Times are median GPU ms over the timed frames.</p>"]
    out += [f'<p class="skipped">{e(n)}</p>' for n in notes]
    out += provenance_section(document) + noise_section(document, rows, limit)
    out.append("<h2>Charts</h2>")
    for chart in charts:
        out += chart_section(chart)
    out += laws_section(laws) + cost_section(model)
    out.append("<h2>Images</h2>")
    if not images:
        out.append('<p class="skipped">No images in images/.</p>')
    for name in images:
        out.append(f'<figure><img src="{href("images/" + name)}" alt="{e(name)}">'
                   f"<figcaption>{e(name)}</figcaption></figure>")
    out += ["<h2>Results</h2>", "<table>",
            "<tr>" + "".join(f"<th>{e(c)}</th>" for c in header) + "</tr>"]
    for row in rows:
        out.append("<tr>" + "".join(f"<td>{e(row.get(c, ''))}</td>" for c in header) + "</tr>")
    out += ["</table>", "</body></html>", ""]
    return "\n".join(out)
