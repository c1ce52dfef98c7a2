#!/usr/bin/python3
"""Side by side, two runs of `punctual bench` (for example lavapipe against a GPU):

    /usr/bin/python3 bench/compare_runs.py DIR_A DIR_B OUT_DIR

reads DIR_A and DIR_B's results.csv (and results.json, for the passes' order and provenance) and
writes OUT_DIR/compare.csv and OUT_DIR/compare.html: for every configuration both runs have (in
run A's order), each pass's median GPU ms in A and B and the ratio B / A, then the counters,
which depend on the scene and settings, not on the device (docs/BENCH_RESULTS.md), and so
should match: a counter that differs by more than a relative COUNTER_TOLERANCE is marked (the
runs did not draw the same work). The page starts with both runs' provenance. Output is
deterministic.

Bad input (a folder or results.csv that is missing or unreadable, a FIFO or a folder where a
file should be, a CSV without a config column, a configuration named twice) prints one line
`compare_runs.py: error: <file>: <problem>` on stderr, exits with status 1 and writes nothing;
a usage error exits with 2. Every file is read by input_file.py's rules (those of punctual's
own reader), so nothing here can block on a FIFO. compare.csv and compare.html change together
or not at all (output_file.py): an interrupt is one line and status 128 + the signal (130 for
Ctrl-C), a write error one line and status 1.
"""

import csv
import html
import io
import os
import sys

PROGRAM = "compare_runs.py"
if __name__ == "__main__":
    # Before the imports below: an interrupt there is one line, not a traceback.
    import output_file
    output_file.exit_quietly_on_interrupt(PROGRAM)

import output_file  # noqa: E402
from bench_data import COUNTERS, fmt, load_document, number, read_names, read_results  # noqa: E402
from input_file import InputFileError  # noqa: E402

COUNTER_TOLERANCE = 1e-4  # relative: counters printed to six digits, rasterised on two devices

# Bad input: the file it concerns and the problem, for the one-line message.
InputError = InputFileError


def read_run(folder):
    """{"folder", "header", "rows" (by config, in file order), "passes", "provenance"}."""
    if not os.path.isdir(folder):
        raise InputError(folder, "not a folder" if os.path.exists(folder) else "no such folder")
    path = os.path.join(folder, "results.csv")
    header, rows = read_results(path)
    if "config" not in header:
        raise InputError(path, "no config column" if header else "empty file")
    by_config = {}
    for r in rows:
        if r["config"] in by_config:
            raise InputError(path, f"configuration {r['config']!r} appears twice")
        by_config[r["config"]] = r
    try:
        document = load_document(os.path.join(folder, "results.json"))
    except ValueError:
        raise InputError(os.path.join(folder, "results.json"), "not valid JSON") from None
    if not isinstance(document, dict):
        document = {}
    names, _ = read_names(None, header, rows, document)
    provenance = document.get("provenance")
    if not isinstance(provenance, dict):
        provenance = {k: document[k] for k in ("device", "scene", "size") if k in document}
    return {"folder": folder, "header": header, "rows": by_config, "passes": names["passes"],
            "provenance": provenance}


def ratio(a, b):
    """b / a, None when either is missing or a is 0."""
    return None if a is None or b is None or a == 0 else b / a


def counters_differ(a, b):
    """True when the two counter cells differ (beyond COUNTER_TOLERANCE for numbers)."""
    x, y = number(a, ""), number(b, "")
    if x is None or y is None:
        return a != b
    return abs(x - y) > COUNTER_TOLERANCE * max(abs(x), abs(y))


def compare(run_a, run_b):
    """(columns, rows of compare.csv, the times and counters compared)."""
    passes = run_a["passes"] + [p for p in run_b["passes"] if p not in run_a["passes"]]
    timed = [p for p in passes if f"{p}_ms" in run_a["header"] or f"{p}_ms" in run_b["header"]]
    timed.append("total")
    counters = [c for c in COUNTERS if c in run_a["header"] or c in run_b["header"]]
    columns = ["config", "series", "method"]
    for p in timed:
        columns += [f"{p}_ms_a", f"{p}_ms_b", f"{p}_ratio"]
    columns.append("counters_differing")
    for c in counters:
        columns += [f"{c}_a", f"{c}_b"]
    out = []
    for config, a in run_a["rows"].items():
        b = run_b["rows"].get(config)
        if b is None:
            continue
        row = {"config": config, "series": a.get("series", ""), "method": a.get("method", "")}
        for p in timed:
            ta, tb = number(a, f"{p}_ms"), number(b, f"{p}_ms")
            row[f"{p}_ms_a"], row[f"{p}_ms_b"] = a.get(f"{p}_ms", ""), b.get(f"{p}_ms", "")
            row[f"{p}_ratio"] = fmt(ratio(ta, tb))
        differing = [c for c in counters if counters_differ({"": a.get(c, "")}, {"": b.get(c, "")})]
        row["counters_differing"] = " ".join(differing)
        for c in counters:
            row[f"{c}_a"], row[f"{c}_b"] = a.get(c, ""), b.get(c, "")
        out.append(row)
    return columns, out, timed, counters


def csv_text(columns, rows):
    buffer = io.StringIO()
    writer = csv.DictWriter(buffer, fieldnames=columns, lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)
    return buffer.getvalue()


def provenance_rows(value, prefix=""):
    """[(dotted key, text)] of a provenance object."""
    if isinstance(value, dict):
        out = []
        for k, v in value.items():
            out += provenance_rows(v, f"{prefix}.{k}" if prefix else str(k))
        return out
    return [(prefix, ", ".join(map(str, value)) if isinstance(value, list) else str(value))]


def html_text(run_a, run_b, rows, timed, counters):
    e = html.escape
    a_facts, b_facts = dict(provenance_rows(run_a["provenance"])), dict(provenance_rows(run_b["provenance"]))
    keys = list(a_facts) + [k for k in b_facts if k not in a_facts]
    out = ["<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
           "<title>punctual bench: two runs compared</title><style>",
           "body { font-family: sans-serif; margin: 1.5em; } table { border-collapse: collapse;"
           " font-size: 0.75em; } th { background: #eee; } th, td { border: 1px solid #bbb;"
           " padding: 2px 5px; text-align: right; } td:first-child, th:first-child"
           " { text-align: left; } .differ { background: #fcc; font-weight: bold; }"
           " .faster { color: #060; } .slower { color: #a00; }",
           "</style></head><body>", "<h1>Two runs compared</h1>",
           f"<p>A: {e(run_a['folder'])}, B: {e(run_b['folder'])}; {len(rows)} configurations "
           f"in both (of {len(run_a['rows'])} in A, {len(run_b['rows'])} in B). Ratios are "
           "B / A of the median GPU ms: under 1, B is faster. Counters should match on any "
           f"device; one that differs by more than a relative {COUNTER_TOLERANCE:g} is marked "
           '<span class="differ">so</span>. The numbers are in '
           '<a href="compare.csv">compare.csv</a>.</p>', "<h2>Provenance</h2>", "<table>",
           "<tr><th></th><th>A</th><th>B</th></tr>"]
    out += [f"<tr><td>{e(k)}</td><td>{e(a_facts.get(k, ''))}</td><td>{e(b_facts.get(k, ''))}"
            "</td></tr>" for k in keys]
    out += ["</table>", "<h2>Times</h2>"]
    if not rows:
        out.append("<p>The runs have no configuration in common.</p>")
    else:
        out += ["<table>", "<tr><th>config</th>" + "".join(
            f"<th>{e(p)} A</th><th>{e(p)} B</th><th>{e(p)} B/A</th>" for p in timed) + "</tr>"]
        for r in rows:
            cells = []
            for p in timed:
                value = number(r, f"{p}_ratio")
                style = "" if value is None else (' class="faster"' if value < 1 else
                                                  ' class="slower"' if value > 1 else "")
                cells.append(f"<td>{e(r[f'{p}_ms_a'])}</td><td>{e(r[f'{p}_ms_b'])}</td>"
                             f"<td{style}>{e(r[f'{p}_ratio'])}</td>")
            out.append(f"<tr><td>{e(r['config'])}</td>{''.join(cells)}</tr>")
        out.append("</table>")
        differing = [r for r in rows if r["counters_differing"]]
        out += ["<h2>Counters</h2>", f"<p>{len(differing)} of {len(rows)} configurations have "
                "a counter that differs.</p>", "<table>", "<tr><th>config</th>" +
                "".join(f"<th>{e(c)}</th>" for c in counters) + "</tr>"]
        for r in rows:
            marked = set(r["counters_differing"].split())
            cells = []
            for c in counters:
                if c in marked:
                    cells.append(f'<td class="differ">{e(r[c + "_a"])} ≠ {e(r[c + "_b"])}</td>')
                else:
                    cells.append(f"<td>{e(r[c + '_a'])}</td>")
            out.append(f"<tr><td>{e(r['config'])}</td>{''.join(cells)}</tr>")
        out.append("</table>")
    out += ["</body></html>", ""]
    return "\n".join(out)


def main(argv=None):
    """Command line entry point; returns the exit status."""
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) != 3:
        print(f"{PROGRAM}: error: usage: {PROGRAM} DIR_A DIR_B OUT_DIR", file=sys.stderr)
        return 2
    return output_file.run_script(PROGRAM, lambda outputs: write_comparison(*argv, outputs))


def write_comparison(dir_a, dir_b, out_dir, outputs):
    """Reads both runs and writes compare.csv and compare.html into `outputs`, committed
    together; returns 0. Bad input raises InputError before OUT_DIR is made."""
    run_a, run_b = read_run(dir_a), read_run(dir_b)
    if os.path.exists(out_dir) and not os.path.isdir(out_dir):
        raise InputError(out_dir, "not a folder")
    columns, rows, timed, counters = compare(run_a, run_b)
    os.makedirs(out_dir, exist_ok=True)
    outputs.write_text(os.path.join(out_dir, "compare.csv"), csv_text(columns, rows))
    outputs.write_text(os.path.join(out_dir, "compare.html"),
                       html_text(run_a, run_b, rows, timed, counters))
    outputs.commit()
    print(f"wrote {os.path.join(out_dir, 'compare.html')} and compare.csv: {len(rows)} "
          "configurations in both runs")
    return 0


if __name__ == "__main__":
    sys.exit(main())
