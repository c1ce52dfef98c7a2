"""The cost model: each pass's median GPU time as a sum of unit costs times the counters that
drive it, fitted over every (unflagged) row of a run by non-negative least squares.

    forward ≈ a·frames + b·pixels + c·pixels·tested_per_pixel + d·pixels·shadow lookups + ...

The counters hold on any device (docs/BENCH_RESULTS.md), so a reader can predict a frame on
another device from its unit costs (ns per unit), or this device's frame for counters it did not
measure. A counter no row has, or that is 0 in every row, is left out of its pass's fit and
named as such; a pass whose work depends on the light-list method (culling) is fitted per
method.
"""

import numpy

from bench_data import is_flagged, light_count, number, pixels


def _product(*columns):
    """pixels times the product of `columns` of a row, None when any is missing."""
    def term(row):
        value = pixels(row)
        for c in columns:
            v = number(row, c)
            value = None if value is None or v is None else value * v
        return value
    return term


def _column(column):
    return lambda row: number(row, column)


FRAME = ("frame", "ns per frame", "1 (the pass's fixed cost)", lambda row: 1.0)
PIXEL = ("pixel", "ns per pixel", "pixels", pixels)
# pass -> its terms: (name, unit, counter expression, value of a row).
MODELS = {
    "depth": [FRAME, PIXEL,
              ("triangle", "ns per triangle", "depth_triangles", _column("depth_triangles")),
              ("draw", "ns per draw", "depth_draws", _column("depth_draws"))],
    "culling": [FRAME, PIXEL,
                ("pixel·light", "ns per pixel x light", "pixels x (spot + point)",
                 lambda row: None if pixels(row) is None else pixels(row) * light_count(row))],
    "shadows": [FRAME,
                ("texel", "ns per shadow texel", "shadow_texels_rendered",
                 _column("shadow_texels_rendered")),
                ("triangle", "ns per triangle", "shadow_triangles", _column("shadow_triangles")),
                ("draw", "ns per draw", "shadow_draws", _column("shadow_draws"))],
    "forward": [FRAME, PIXEL,
                ("light test", "ns per light tested", "pixels x tested_per_pixel",
                 _product("tested_per_pixel")),
                ("shadow lookup", "ns per lookup", "pixels x shadow_lookups_per_pixel",
                 _product("shadow_lookups_per_pixel")),
                ("filter tap", "ns per tap", "pixels x filter_taps_per_pixel",
                 _product("filter_taps_per_pixel")),
                ("triangle", "ns per triangle", "forward_triangles", _column("forward_triangles")),
                ("draw", "ns per draw", "forward_draws", _column("forward_draws"))],
    "transparent": [FRAME, PIXEL,
                    ("triangle", "ns per triangle", "transparent_triangles",
                     _column("transparent_triangles")),
                    ("draw", "ns per draw", "transparent_draws", _column("transparent_draws"))],
}
DEFAULT_MODEL = [FRAME, PIXEL]  # any other pass (tonemap, a new one): fixed plus per pixel
PER_METHOD = {"culling"}  # passes whose unit costs depend on the method


def nnls(a, b, max_iterations=None):
    """x >= 0 minimising |a x - b| (Lawson and Hanson's active set method), for a small dense a.
    The columns are scaled to unit norm first (a column of zeros gets 0)."""
    a = numpy.asarray(a, dtype=float)
    b = numpy.asarray(b, dtype=float)
    norms = numpy.linalg.norm(a, axis=0)
    live = norms > 0
    scaled = a[:, live] / norms[live]
    n = scaled.shape[1]
    x = numpy.zeros(n)
    passive = numpy.zeros(n, dtype=bool)
    tolerance = 1e-10 * max(1.0, float(numpy.linalg.norm(b)))
    for _ in range(max_iterations or 3 * n + 10):
        w = scaled.T @ (b - scaled @ x)
        if passive.all() or w[~passive].max() <= tolerance:
            break
        passive[numpy.argmax(numpy.where(passive, -numpy.inf, w))] = True
        while True:
            s = numpy.zeros(n)
            s[passive] = numpy.linalg.lstsq(scaled[:, passive], b, rcond=None)[0]
            if (s[passive] > 0).all():
                x = s
                break
            shrink = passive & (s <= 0)
            alpha = numpy.min(x[shrink] / (x[shrink] - s[shrink]))
            x = x + alpha * (s - x)
            passive &= x > 1e-15
            x[~passive] = 0.0
    result = numpy.zeros(a.shape[1])
    result[live] = x / norms[live]
    return result


def r_squared(actual, predicted):
    """1 - residual sum of squares / total sum of squares (1 when both are 0)."""
    actual, predicted = numpy.asarray(actual, float), numpy.asarray(predicted, float)
    total = float(((actual - actual.mean()) ** 2).sum())
    residual = float(((actual - predicted) ** 2).sum())
    if total == 0:
        return 1.0 if residual == 0 else 0.0
    return 1.0 - residual / total


def significant(value, digits=6):
    """A float rounded to `digits` significant digits (stable text in JSON and HTML)."""
    return float(f"{value:.{digits}g}")


def fit_pass(rows, name, terms):
    """The fit of `name`_ms over `rows` against `terms`; a dict for cost_model.json, or None when
    no row has the pass's time and every term's counter."""
    column = f"{name}_ms"
    present = [t for t in terms if any(t[3](r) is not None for r in rows)]
    missing = [t[2] for t in terms if t not in present]
    used = [r for r in rows if number(r, column) is not None and not is_flagged(r)
            and all(t[3](r) is not None for t in present)]
    if not used or not present:
        return None
    exercised = [t for t in present if any(t[3](r) for r in used)]
    idle = [t[2] for t in present if t not in exercised]
    a = [[t[3](r) for t in exercised] for r in used]
    b = [number(r, column) for r in used]
    costs = nnls(a, b) if exercised else numpy.zeros(0)
    predicted = numpy.asarray(a, float) @ costs if exercised else numpy.zeros(len(b))
    return {
        "pass": name, "rows": len(used), "r2": significant(r_squared(b, predicted), 4),
        "terms": [{"term": t[0], "counter": t[2], "unit": t[1],
                   "ns": significant(float(c) * 1e6)} for t, c in zip(exercised, costs)],
        "not_in_data": missing, "zero_in_every_row": idle,
        "predict": lambda row, ts=exercised, cs=costs: sum(
            float(c) * (t[3](row) or 0.0) for t, c in zip(ts, cs)),
    }


def fit_cost_model(rows, passes):
    """Every pass's fit (culling per method) and how well their sum predicts total_ms: a dict
    {"fits": [...], "total": {...}} whose fits keep a "predict" function (dropped by
    model_document)."""
    fits = []
    for name in passes:
        terms = MODELS.get(name, DEFAULT_MODEL)
        if name in PER_METHOD:
            methods = sorted({r.get("method", "") for r in rows})
            groups = [(m, [r for r in rows if r.get("method", "") == m]) for m in methods]
        else:
            groups = [("", rows)]
        for method, own in groups:
            fit = fit_pass(own, name, terms)
            if fit is not None:
                fit["method"] = method
                fits.append(fit)
    actual, predicted = [], []
    for r in rows:
        total = number(r, "total_ms")
        if total is None or is_flagged(r):
            continue
        relevant = [f for f in fits if f["method"] in ("", r.get("method", ""))]
        if relevant and all(number(r, f"{f['pass']}_ms") is not None for f in relevant):
            actual.append(total)
            predicted.append(sum(f["predict"](r) for f in relevant))
    total = {"rows": len(actual)}
    if actual:
        total["r2"] = significant(r_squared(actual, predicted), 4)
        errors = sorted(abs(p - t) / t for p, t in zip(predicted, actual) if t > 0)
        if errors:
            total["median_relative_error"] = significant(errors[len(errors) // 2], 4)
    return {"fits": fits, "total": total}


def model_document(model):
    """cost_model.json's contents (the fits without their predict functions)."""
    fits = [{k: v for k, v in f.items() if k != "predict"} for f in model["fits"]]
    for f in fits:
        if not f["method"]:
            del f["method"]
    return {"fit": "non-negative least squares of each pass's median GPU ms against its "
                   "counters, over every unflagged row; costs in ns per unit",
            "passes": fits,
            "total": dict(model["total"], note="whole frame predicted as the sum of the fitted "
                                               "passes (time between passes not modelled)")}
