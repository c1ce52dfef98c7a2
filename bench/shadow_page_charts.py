"""The shadow-memory series' chart (issue 33): whole views (--shadow-res auto) against virtual
shadow pages (--shadow-res virtual) on each scene, as two Pareto panels: shadow memory and the
shadow stage's GPU time, each against the shadow tests misclassified outside the edge band
(against Embree). A scene's two modes are joined by a line, so where virtual pages win and where
they lose reads at a glance. And the growth chart: each mode's memory against the pairs the frame
shades (the floor) and against the views it renders. Drawn by plot_results.py."""

from bench_data import number, pareto_front, series_rows
from chart_style import SkipChart, add_flagged_legend, draw_front, plt
from matplotlib.ticker import PercentFormatter

SERIES = "shadow-memory"
MODE_MARKERS = {"auto": "o", "virtual": "s"}


def shadow_stage_ms(row):
    """The shadow stage: the marking passes (virtual pages only) and the shadow pass."""
    parts = [number(row, c) for c in ("shadow_marks_ms", "shadow_marks_transparent_ms", "shadows_ms")]
    return None if parts[2] is None else sum(p for p in parts if p is not None)


def scene_label(row):
    """A built-in scene with its own lights (with its triangles), or the bench's scene with its
    first generated lights (the rows with a light_range), its name without "built-in ... scene"."""
    name = row.get("scene", "").removeprefix("built-in ").removesuffix(" scene")
    if row.get("light_range", ""):
        return f"{name}, {int(float(row.get('spot', 0) or 0))} + {int(float(row.get('point', 0) or 0))} lights"
    triangles = row.get("scene_triangles", "")
    return f"{name} ({int(float(triangles)):,} tri)" if triangles else name


def chart_virtual_pages(rows, names):
    """Virtual shadow pages against whole views (the shadow-memory series): shadow memory (left)
    and the shadow stage's median GPU time, marking included (right), against the shadow tests
    misclassified outside the edge band (against Embree), one point per scene and mode, a scene's
    two modes joined. Circles: --shadow-res auto; squares: virtual. The Pareto front marks the
    points no other beats on both axes."""
    rs = [r for r in series_rows(rows, SERIES)
          if number(r, "shadow_memory_bytes") is not None and number(r, "shadow_misclassified") is not None
          and shadow_stage_ms(r) is not None]
    if not rs:
        raise SkipChart(f"no {SERIES} rows with shadow_memory_bytes, shadows_ms and shadow_misclassified")
    scenes = []
    for r in rs:
        if scene_label(r) not in scenes:
            scenes.append(scene_label(r))
    cmap = plt.get_cmap("tab10")
    fig, axes = plt.subplots(1, 2, figsize=(12, 5.2))
    panels = [(axes[0], lambda r: number(r, "shadow_memory_bytes") / 2**20, "shadow memory, MiB"),
              (axes[1], shadow_stage_ms, "shadow stage (marking + drawing): median GPU ms")]
    for ax, cost, label in panels:
        points = [(number(r, "shadow_misclassified"), cost(r)) for r in rs]
        for k, scene in enumerate(scenes):
            mine = [(p, r) for p, r in zip(points, rs) if scene_label(r) == scene]
            ax.plot([p[0] for p, _ in mine], [p[1] for p, _ in mine], color=cmap(k % 10), linewidth=0.8, zorder=1)
            for p, r in mine:
                mode = r.get("shadow_res", "")
                ax.scatter([p[0]], [p[1]], color=cmap(k % 10), marker=MODE_MARKERS.get(mode, "^"), zorder=2,
                           label=f"{scene}: {mode}")
        draw_front(ax, points, pareto_front(points))
        ax.set_yscale("log")
        ax.xaxis.set_major_formatter(PercentFormatter(xmax=1.0))
        ax.set_xlabel("shadow tests misclassified outside the edge band (lower is better)")
        ax.set_ylabel(f"{label} (lower is better)")
    add_flagged_legend(axes[1], fontsize=7)
    fig.suptitle("Virtual shadow pages against whole views: memory and time against accuracy")
    fig.tight_layout()
    return fig


def chart_virtual_page_growth(rows, names):
    """Shadow memory's growth (the shadow-memory series): each configuration's shadow memory
    against the floor, one 16-bit texel per shaded (pixel, light) pair (left), and against the
    shadow views rendered (right), log-log. Circles: --shadow-res auto; squares: virtual. Virtual
    pages should follow the floor (the dotted lines: 1x and 3x the floor) whatever the view count;
    whole views follow the views until the budget stops them."""
    rs = [r for r in series_rows(rows, SERIES)
          if number(r, "shadow_memory_bytes") is not None and number(r, "shadow_floor_bytes")
          and number(r, "shadow_views")]
    if not rs:
        raise SkipChart(f"no {SERIES} rows with shadow_memory_bytes, shadow_floor_bytes and shadow_views")
    cmap = plt.get_cmap("tab10")
    fig, axes = plt.subplots(1, 2, figsize=(12, 5.2))
    mib = 2.0 ** -20
    panels = [(axes[0], lambda r: number(r, "shadow_floor_bytes") * mib, "floor: shaded pairs x 2 bytes, MiB"),
              (axes[1], lambda r: number(r, "shadow_views"), "shadow views rendered")]
    modes = []
    for r in rs:
        if r.get("shadow_res", "") not in modes:
            modes.append(r.get("shadow_res", ""))
    for ax, x, label in panels:
        for k, mode in enumerate(modes):
            mine = sorted((r for r in rs if r.get("shadow_res", "") == mode), key=x)
            ax.scatter([x(r) for r in mine], [number(r, "shadow_memory_bytes") * mib for r in mine],
                       color=cmap(k % 10), marker=MODE_MARKERS.get(mode, "^"), label=mode, zorder=2)
            for r in mine:
                ax.annotate(scene_label(r), (x(r), number(r, "shadow_memory_bytes") * mib), fontsize=6,
                            xytext=(3, 3), textcoords="offset points")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(label)
        ax.set_ylabel("shadow memory, MiB")
    floors = sorted(number(r, "shadow_floor_bytes") * mib for r in rs)
    for times, style in ((1.0, ":"), (3.0, "--")):
        axes[0].plot([floors[0], floors[-1]], [times * floors[0], times * floors[-1]], color="grey", linestyle=style,
                     linewidth=0.8, label=f"{times:g}x the floor", zorder=1)
    axes[0].legend(fontsize=7)
    fig.suptitle("Shadow memory against the pairs shaded and the views rendered")
    fig.tight_layout()
    return fig
