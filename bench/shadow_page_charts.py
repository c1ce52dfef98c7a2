"""The shadow-memory series' chart (issue 33): whole views (--shadow-res auto) against virtual
shadow pages (--shadow-res virtual) on each scene, as two Pareto panels: shadow memory and the
shadow stage's GPU time, each against the shadow tests misclassified outside the edge band
(against Embree). A scene's two modes are joined by a line, so where virtual pages win and where
they lose reads at a glance. Drawn by plot_results.py."""

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
    label = row.get("scene", "")
    triangles = row.get("scene_triangles", "")
    return f"{label} ({int(float(triangles)):,} tri)" if triangles else label


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
