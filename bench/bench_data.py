"""Reading a bench folder: results.csv's rows and columns, results.json's names, provenance and
noise, and the helpers every chart shares (numbers, light counts, method styles, spreads, flags).

The columns are those of docs/BENCH_RESULTS.md. Per pass P: P_ms (median over the rounds),
P_iqr_ms (interquartile range) and P_cv (coefficient of variation); a folder from an older bench
has P_spread_ms instead, read as the spread when P_iqr_ms is absent.
"""

import csv
import io
import json
import math

from input_file import InputFileError, read_text

# The columns every row has besides the per-pass times (see pass_columns).
LEADING_COLUMNS = """config series method spot point light_range width height pixels scene
    scene_triangles shadows shadow_res shadow_budget_mib shadow_format shadow_filter point_layout
    cascades shadowed_spots shadowed_points rounds""".split()
TRAILING_COLUMNS = """total_ms total_iqr_ms total_cv flagged flag_reason tested_per_pixel
    affecting_per_pixel shadow_lookups_per_pixel filter_taps_per_pixel shadow_texels_rendered
    depth_triangles forward_triangles transparent_triangles shadow_triangles depth_draws
    forward_draws transparent_draws shadow_draws shadow_draws_max shadow_views shadow_memory_bytes
    shadow_floor_bytes light_grid_bytes light_grid_floor_bytes scene_bytes frame_bytes device_bytes peak_rss_bytes efficiency missed_energy
    image_error pixels_off shadow_misclassified shadow_misclassified_all shadow_misclassified_1px
    shadow_false_shadow shadow_false_lit sun_misclassified sun_misclassified_1px
    sun_cascade0_misclassified_1px sun_cascade1_misclassified_1px sun_cascade2_misclassified_1px
    sun_cascade3_misclassified_1px""".split()
# The counters of docs/BENCH_RESULTS.md: they depend on the scene and settings, not on the
# device, so two runs of one configuration should agree on them (compare_runs.py).
COUNTERS = """tested_per_pixel affecting_per_pixel shadow_lookups_per_pixel filter_taps_per_pixel
    shadow_texels_rendered depth_triangles forward_triangles transparent_triangles shadow_triangles
    depth_draws forward_draws transparent_draws shadow_draws shadow_draws_max shadow_views
    shadow_memory_bytes light_grid_bytes light_grid_floor_bytes scene_bytes frame_bytes""".split()
# Method styles by position in results.json's "methods": the first four keep the colours the
# charts have always had (brute, per-object, tiled, clustered). Grey and "x" are left out: they
# mark a method that results.json does not list.
METHOD_COLOURS = ["tab:red", "tab:orange", "tab:blue", "tab:green", "tab:purple", "tab:brown",
                  "tab:pink", "tab:olive", "tab:cyan"]
METHOD_MARKERS = ["o", "s", "^", "D", "v", "P", "*", "h"]  # 8 against 9 colours: 72 pairs
OTHER_STYLE = ("tab:gray", "x")  # a method in the rows that results.json does not list
WIDE_RATIO = 10.0  # a log axis once the largest value is this many times the smallest
FLAG_LIMIT = 0.15  # total_iqr_ms / total_ms above which a row is flagged, when results.json lacks it
NAME_KEYS = ("methods", "shadow_filters", "passes")


def pass_columns(passes):
    """The per-pass columns of results.csv: P_ms, then P_iqr_ms, then P_cv, for every pass."""
    return ([f"{p}_ms" for p in passes] + [f"{p}_iqr_ms" for p in passes] +
            [f"{p}_cv" for p in passes])


def known_columns(passes):
    """Every column a row of results.csv should have, for these passes."""
    return LEADING_COLUMNS + pass_columns(passes) + TRAILING_COLUMNS


def passes_in_header(header):
    """Pass names of the P_ms columns in `header` (not total_ms, not the spreads), sorted."""
    return sorted(c[:-len("_ms")] for c in header
                  if c.endswith("_ms") and not c.endswith(("_spread_ms", "_iqr_ms"))
                  and c != "total_ms")


def load_document(path):
    """results.json as parsed JSON; {} when the file is absent (an older bench). Raises
    InputFileError when something else is at the path (a FIFO, a directory, an unreadable
    file: input_file.py's rules) and ValueError when it is not JSON."""
    try:
        text = read_text(path)
    except InputFileError as err:
        if err.absent:
            return {}
        raise
    return json.loads(text)


def read_document(path):
    """(results.json as a dict, notes): {} without notes when the file is absent or not an
    object, {} and a note when it is not valid JSON. Raises InputFileError when the path holds
    no regular file (a FIFO, a directory) or it cannot be read: the folder is broken."""
    try:
        document = load_document(path)
    except ValueError as err:
        return {}, [f"results.json could not be read ({err}); names come from results.csv."]
    return (document, []) if isinstance(document, dict) else ({}, [])


def read_names(path, header, rows, document=None):
    """{"methods", "shadow_filters", "passes": names in order} from results.json, and notes.

    A key that results.json lacks (an older bench), or the whole file when it is absent or
    unreadable, falls back to what results.csv holds, sorted: the methods and filters of the rows,
    the passes of the P_ms columns. The notes say which keys fell back and why."""
    notes = []
    if document is None:
        document, notes = read_document(path)
    fallback = {"methods": sorted({r.get("method", "") for r in rows} - {""}),
                "shadow_filters": sorted({r.get("shadow_filter", "") for r in rows} - {""}),
                "passes": passes_in_header(header)}
    names, fell_back = {}, []
    for key in NAME_KEYS:
        listed = document.get(key)
        if isinstance(listed, list) and all(isinstance(n, str) for n in listed):
            names[key] = list(listed)
        else:
            names[key] = fallback[key]
            fell_back.append(key)
    if document and fell_back:
        notes.append(f"results.json lacks {', '.join(fell_back)}; taken from results.csv, sorted.")
    # The grid methods' list forms, the default first (runs before them had none: no note).
    forms = document.get("light_lists")
    names["light_lists"] = (list(forms) if isinstance(forms, list) and all(isinstance(n, str) for n in forms)
                            else sorted({r.get("light_lists", "") for r in rows} - {""}))
    return names, notes


def read_results(path):
    """Returns (header, rows) of the CSV; rows are dicts of strings, missing cells are ''.
    Raises InputFileError when the file cannot be read (input_file.py's rules) or parsed."""
    text = read_text(path)
    try:
        reader = csv.DictReader(io.StringIO(text, newline=""))
        header = list(reader.fieldnames or [])
        rows = [{k: (v or "").strip() for k, v in row.items() if k is not None} for row in reader]
    except csv.Error as err:
        raise InputFileError(path, f"not a valid CSV file ({err})") from None
    return header, rows


def number(row, column):
    """The cell as a finite float, or None when it is empty, missing or not a number."""
    try:
        value = float(row.get(column) or "")
    except ValueError:
        return None
    return value if math.isfinite(value) else None


def light_count(row):
    """Spot plus point lights of a row (0 for missing counts)."""
    return int((number(row, "spot") or 0) + (number(row, "point") or 0))


def pixels(row):
    """The frame's pixels: the pixels column, else width x height, else None."""
    value = number(row, "pixels")
    if value is None and number(row, "width") is not None and number(row, "height") is not None:
        value = number(row, "width") * number(row, "height")
    return value


def spread(row, column):
    """The interquartile range of a time column ("forward_ms" -> forward_iqr_ms), falling back to
    an older bench's forward_spread_ms; None when neither is there."""
    base = column[:-len("_ms")] if column.endswith("_ms") else column
    value = number(row, f"{base}_iqr_ms")
    return value if value is not None else number(row, f"{base}_spread_ms")


def flag_limit(document):
    """results.json's noise.flag_limit, else FLAG_LIMIT."""
    noise = document.get("noise") if isinstance(document, dict) else None
    limit = noise.get("flag_limit") if isinstance(noise, dict) else None
    return float(limit) if isinstance(limit, (int, float)) and limit > 0 else FLAG_LIMIT


def mark_flags(rows, limit):
    """Sets row["flagged"] to "1" or "0" where the bench left it empty: 1 when total_iqr_ms
    exceeds `limit` x total_ms (the contract's rule). A row with neither keeps an empty cell."""
    for r in rows:
        if number(r, "flagged") is not None:
            continue
        iqr, total = number(r, "total_iqr_ms"), number(r, "total_ms")
        if iqr is not None and total is not None:
            flagged = iqr > limit * total
            r["flagged"] = "1" if flagged else "0"
            if flagged and not r.get("flag_reason"):
                r["flag_reason"] = f"total_iqr_ms > {limit:g} x total_ms"


def is_flagged(row):
    """True when the bench (or mark_flags) flagged the row: its spread exceeds the limit."""
    return bool(number(row, "flagged"))


def flagged_rows(rows):
    """The flagged rows, in file order."""
    return [r for r in rows if is_flagged(r)]


def series_rows(rows, series):
    """The rows of one series, in file order."""
    return [r for r in rows if r.get("series") == series]


def ordered(present, names):
    """`present` values in the order of `names`, then any others sorted."""
    present = set(present)
    return [n for n in names if n in present] + sorted(present - set(names))


def method_order(rows, methods):
    """The methods present in `rows`: those of `methods` in its order, then any others sorted."""
    return ordered((r.get("method", "") for r in rows), methods)


def method_style(method, methods):
    """(colour, marker) of a method: by its position in `methods`, OTHER_STYLE when absent."""
    if method not in methods:
        return OTHER_STYLE
    i = methods.index(method)
    return METHOD_COLOURS[i % len(METHOD_COLOURS)], METHOD_MARKERS[i % len(METHOD_MARKERS)]


def is_wide(values):
    """True when the positive values span more than WIDE_RATIO (and none is <= 0)."""
    values = [v for v in values if v is not None]
    return bool(values) and min(values) > 0 and max(values) / min(values) > WIDE_RATIO


def varying_label(row, rows, fields):
    """A label made of those `fields` whose values differ between `rows` (empty values left out)."""
    varying = [f for f in fields if len({r.get(f, "") for r in rows}) > 1] or fields[:1]
    return " ".join(row.get(f, "") for f in varying if row.get(f, ""))


def pareto_front(points):
    """Indices of the non-dominated (x, y) points, both lower-is-better, sorted by x then y: no
    other point is at least as good in both and better in one. Equal points are all kept."""
    order = sorted(range(len(points)), key=lambda i: (points[i][0], points[i][1]))
    front, best_y = [], math.inf
    for i in order:
        x, y = points[i]
        if y < best_y or (front and points[front[-1]] == (x, y)):
            front.append(i)
            best_y = min(best_y, y)
    return front


def median(values):
    """The median of a non-empty list of numbers."""
    values = sorted(values)
    mid = len(values) // 2
    return values[mid] if len(values) % 2 else (values[mid - 1] + values[mid]) / 2


def fmt(value, digits=4):
    """A number in `digits` significant digits (deterministic text for pages and JSON)."""
    return "" if value is None else f"{value:.{digits}g}"
