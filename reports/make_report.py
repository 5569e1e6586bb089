#!/usr/bin/python3
"""cutbench report: a static HTML site from a results directory.

Reads <results>/manifest.json (written by `cutbench report`). Each case carries two verdicts: the
paper-resolution one (a recorded full-tier run, reports/full_tier/<paper>/<item>.json, or the
analytic evaluation) and the regression one (the quick tier of this results directory, reduced
resolution). The index counts the paper-resolution verdicts and checks per paper (by kind and
status; consistency checks apart); each paper page opens with one table of its items, then each
case leads with its paper-resolution verdict and checks, its figures (drawn from the full-tier
HDF5 where the record has one, else from the quick tier, each labelled with its tier), and the
regression checks below. benchmarks/<paper>/FINDINGS.md becomes findings-<paper>.html, with an
anchor per finding id; known failures link to their finding.
Run with Debian's /usr/bin/python3 (h5py, matplotlib, numpy).
"""
import argparse
import csv
import html
import json
import math
import os
import re
import sys
import textwrap

os.environ.setdefault("MPLBACKEND", "Agg")
import matplotlib  # noqa: E402

matplotlib.use("Agg")
matplotlib.rcParams["svg.hashsalt"] = "cutbench"
matplotlib.rcParams["path.simplify"] = False
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

try:
    import h5py  # noqa: E402
except ImportError:  # pragma: no cover
    sys.exit("make_report.py: h5py missing; run scripts/setup-debian.sh and use /usr/bin/python3")

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import report_md  # noqa: E402

UNITS = {  # symbol -> (factor to SI, offset)
    "1": (1, 0), "-": (1, 0), "%": (0.01, 0), "m": (1, 0), "mm": (1e-3, 0), "um": (1e-6, 0),
    "rad": (1, 0), "deg": (math.pi / 180, 0), "Pa": (1, 0), "kPa": (1e3, 0), "MPa": (1e6, 0),
    "GPa": (1e9, 0), "N": (1, 0), "kN": (1e3, 0), "N/m": (1, 0), "N/mm": (1e3, 0), "J/m^2": (1, 0),
    "s": (1, 0), "ms": (1e-3, 0), "us": (1e-6, 0), "m/s": (1, 0), "m/min": (1 / 60, 0),
    "mm/min": (1e-3 / 60, 0), "K": (1, 0), "kg/m^3": (1, 0), "g/cm^3": (1e3, 0), "1/m": (1, 0),
    "N m/m": (1, 0), "Pa m^0.5": (1, 0), "MPa m^0.5": (1e6, 0),
}
STATUS_CLASS = {"PASS": "pass", "FAIL": "fail", "FAIL (known)": "known", "ERROR": "error",
                "INCONCLUSIVE": "inconcl", "NOT RUN": "notrun", "NOT IMPLEMENTED": "ni", "NOT YET RUN": "nyr"}
STYLES = {"solid": dict(ls="-"), "dashed": dict(ls="--"), "dotted": dict(ls=":"),
          "markers": dict(ls="none", marker="o", ms=5, mfc="none"),
          "line+markers": dict(ls="-", marker="s", ms=4)}


def convert(values, from_unit, to_unit):
    """Convert an array between units (both in UNITS)."""
    if to_unit is None or from_unit == to_unit:
        return values
    fa, oa = UNITS.get(from_unit, (1, 0))
    fb, ob = UNITS.get(to_unit, (1, 0))
    return (np.asarray(values) * fa + oa - ob) / fb


def axis_unit(label, default):
    """The unit in a trailing '(unit)' of an axis label, if it is one of UNITS; else `default`."""
    m = re.search(r"\(([^()]*)\)\s*$", label or "")
    return m.group(1) if m and m.group(1) in UNITS else default


def read_reference(path):
    meta, header, rows = {}, None, []
    with open(path, newline="") as f:
        for line in f:
            s = line.strip()
            if not s:
                continue
            if s.startswith("#"):
                if ":" in s:
                    k, v = s[1:].split(":", 1)
                    k = k.strip()
                    if " " not in k:
                        meta[k] = (meta.get(k, "") + " " + v.strip()).strip()
                continue
            cells = next(csv.reader([s]))
            if header is None:
                header = [c.strip() for c in cells]
            else:
                rows.append([c.strip() for c in cells])
    cols = {}
    for i, h in enumerate(header or []):
        name, unit = (h.split("[", 1)[0].strip(), h.split("[", 1)[1].rstrip("]").strip()) if "[" in h else (h, None)
        cols[name] = (unit, [r[i] if i < len(r) else "" for r in rows])
    return meta, cols


def ref_xy(root, paper, line):
    meta, cols = read_reference(os.path.join(root, "reference_data", paper, line["reference"]))
    where = line.get("where", {})
    n = len(next(iter(cols.values()))[1]) if cols else 0
    keep = [i for i in range(n)
            if all(cols[k][1][i] == str(v) or _num_eq(cols[k][1][i], v) for k, v in where.items())]
    xu, xs = cols[line["x"]]
    yu, ys = cols[line["y"]]
    x = np.array([float(xs[i]) if xs[i] else np.nan for i in keep])
    y = np.array([float(ys[i]) if ys[i] else np.nan for i in keep])
    x = convert(convert(x, xu, "1" if xu is None else xu), xu, line.get("x_unit", xu))
    y = convert(y, yu, line.get("y_unit", yu))
    return x, y


def _num_eq(cell, v):
    try:
        return abs(float(cell) - float(v)) <= 1e-12 * max(1.0, abs(float(v)))
    except (TypeError, ValueError):
        return False


def h5_xy(h5, line):
    g = h5["series"][line["series"]]
    if "run" in line:
        g = g["point_%d" % int(line["run"])][line.get("table", "forces")]
    x = g[line["x"]][()]
    y = g[line["y"]][()]
    xu = g[line["x"]].attrs.get("units", "1")
    yu = g[line["y"]].attrs.get("units", "1")
    xu = xu.decode() if isinstance(xu, bytes) else xu
    yu = yu.decode() if isinstance(yu, bytes) else yu
    return convert(x, xu, line.get("x_unit")), convert(y, yu, line.get("y_unit")) * line.get("y_scale", 1.0)


def particle_spacing(x, y, sample=400):
    """Median nearest-neighbour distance of a sample of points (the particle spacing of a lattice)."""
    n = len(x)
    if n < 2:
        return 1.0
    idx = np.linspace(0, n - 1, min(sample, n)).astype(int)
    d = []
    for i in idx:
        r2 = (x - x[i]) ** 2 + (y - y[i]) ** 2
        r2[i] = np.inf
        d.append(math.sqrt(r2.min()))
    return float(np.median(d))


def draw_F_glyphs(ax, sx, sy, F, c, plot, norm=None, facecolor="0.85", edgecolor="0.25"):
    """Deformation-gradient glyphs: each particle's domain, a square of the particle spacing in the
    reference configuration, drawn deformed by its F (the parallelograms of Nairn 2015 Fig. 2).
    `F`: (n, 4) rows F_xx, F_xy, F_yx, F_yy; `c`: colour values (None: `facecolor`)."""
    from matplotlib.collections import PolyCollection
    F = np.asarray(F, dtype=float).reshape(-1, 2, 2)
    a = 0.5 * particle_spacing(sx, sy)
    corners = np.array([[-a, -a], [a, -a], [a, a], [-a, a]])
    verts = np.einsum("pij,cj->pci", F, corners) + np.stack([sx, sy], axis=1)[:, None, :]
    pc = PolyCollection(verts, cmap=plot.get("cmap", "Greys"), norm=norm, edgecolors=edgecolor, linewidths=0.15)
    if c is not None:
        pc.set_array(np.asarray(c, dtype=float))
    else:
        pc.set_facecolor(facecolor)
    ax.add_collection(pc)
    ax.autoscale_view()
    return pc


def _attr(obj, name, default=""):
    v = obj.attrs.get(name, default)
    return v.decode() if isinstance(v, bytes) else v


def display_values(values, unit):
    """A field in the unit it is best read in: stresses of 1e5 Pa and above in MPa."""
    v = np.asarray(values, dtype=float)
    if unit == "Pa":
        finite = np.abs(v[np.isfinite(v)])
        if finite.size and np.percentile(finite, 99) >= 1e5:
            return v / 1e6, "MPa"
    return v, unit


def field_label(name, unit, plot):
    """Colour-bar label: the case's `clabel` (or the field name) with the field's units."""
    label = plot.get("clabel") or name
    if unit in ("1", "-", "", None):
        return label if "dimensionless" in label else label + " (dimensionless)"
    return label if "(%s)" % unit in label else "%s (%s)" % (label, unit)


def field_norm(values, plot, sample=None):
    """Colour normalisation of a [[plots]] entry. Linear by default; `norm = "log"` draws values
    below `vmin` at `vmin` (default vmin = vmax / 10^decades, decades = 3). `vmin`/`vmax` fix the
    range; without them the range is the 1st to 99th percentile of the values (of `sample`, a
    subset, when given), so that no single particle sets the colour scale. The colour bar shows an
    arrow at each end where values lie beyond the range. Returns (norm, values, extend)."""
    from matplotlib.colors import LogNorm, Normalize
    v = np.asarray(values, dtype=float)
    s = v if sample is None else np.asarray(sample, dtype=float)
    finite = s[np.isfinite(s)]
    lo = float(finite.min()) if finite.size else 0.0
    hi = float(finite.max()) if finite.size else 1.0
    p1, p99 = (float(x) for x in np.percentile(finite, [1, 99])) if finite.size else (lo, hi)
    if p99 <= p1:  # (nearly) constant apart from a few values: show them all
        p1, p99 = lo, hi
    log = plot.get("norm") == "log"
    if log:
        pos = finite[finite > 0]
        vmax = float(plot["vmax"]) if "vmax" in plot else (float(np.percentile(pos, 99)) if pos.size else 1.0)
        vmax = vmax if vmax > 0 else 1.0
        vmin = float(plot["vmin"]) if "vmin" in plot else vmax * 10.0 ** -float(plot.get("decades", 3))
    else:
        vmax = float(plot["vmax"]) if "vmax" in plot else p99
        vmin = float(plot["vmin"]) if "vmin" in plot else p1
        if vmax <= vmin:  # a constant field (e.g. no damage yet): 0 at the bottom of [0, 1]
            vmin, vmax = (0.0, 1.0) if vmin == 0 else (vmin - 0.5 * abs(vmin), vmax + 0.5 * abs(vmax))
    eps = 1e-9 * max(abs(vmin), abs(vmax), 1e-300)
    extend = {(True, True): "both", (True, False): "min", (False, True): "max",
              (False, False): "neither"}[(lo < vmin - eps, hi > vmax + eps)]
    if log:
        return LogNorm(vmin=vmin, vmax=vmax), np.clip(v, vmin, None), extend
    return Normalize(vmin=vmin, vmax=vmax), v, extend


def colour_bar(fig, ax, mappable, extend, label):
    """A colour bar as tall as the (equal-aspect) axes, with arrows at clipped ends."""
    from mpl_toolkits.axes_grid1 import make_axes_locatable
    cax = make_axes_locatable(ax).append_axes("right", size="3.5%", pad=0.12)
    cb = fig.colorbar(mappable, cax=cax, extend=extend)
    cb.set_label(label, fontsize=9)
    cb.ax.tick_params(labelsize=8)
    return cb


def convex_hull(points):
    """Convex hull (monotone chain) of 2-D points, counter-clockwise, as an (m, 2) array."""
    pts = sorted(set(map(tuple, np.asarray(points, dtype=float).tolist())))
    if len(pts) < 3:
        return np.array(pts)

    def half(seq):
        h = []
        for p in seq:
            while len(h) >= 2 and ((h[-1][0] - h[-2][0]) * (p[1] - h[-2][1]) -
                                   (h[-1][1] - h[-2][1]) * (p[0] - h[-2][0])) <= 0:
                h.pop()
            h.append(p)
        return h
    lower, upper = half(pts), half(reversed(pts))
    return np.array(lower[:-1] + upper[:-1])


TOOL_FACE, TOOL_EDGE = "#c6dbef", "#08519c"


def draw_tool(ax, snap, sx, sy, tool, x_unit, y_unit):
    """The tool, where the snapshot describes it: a `tool_outline` dataset ((n, 2) in metres), else
    its particles (the `rigid` flag of the MPM snapshots), drawn as their convex hull. Returns True
    when something was drawn."""
    from matplotlib.patches import Polygon
    if "tool_outline" in snap:
        xy = np.asarray(snap["tool_outline"][()], dtype=float).reshape(-1, 2)
        poly = np.stack([convert(xy[:, 0], "m", x_unit), convert(xy[:, 1], "m", y_unit)], axis=1)
    elif tool is not None and tool.sum() >= 3:
        poly = convex_hull(np.stack([sx[tool], sy[tool]], axis=1))
    else:
        return False
    if len(poly) < 3:
        return False
    ax.add_patch(Polygon(poly, closed=True, facecolor="none", edgecolor=TOOL_EDGE, lw=1.0, zorder=4,
                         label="tool"))
    return True


def element_edges(cells, parent):
    """Edges of the parent elements of a sub-triangulated mesh: the edges of `cells` that lie on
    the boundary or between cells of different parents (`parent` per cell)."""
    seen = {}
    for c, tri in enumerate(cells):
        for a, b in ((tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])):
            key = (a, b) if a < b else (b, a)
            if key in seen:
                if seen[key] is not None and parent[seen[key]] == parent[c]:
                    seen[key] = None  # interior to one element
                elif seen[key] is not None:
                    seen[key] = -1  # between two elements: keep
            else:
                seen[key] = c
    return [k for k, v in seen.items() if v is not None]


def draw_mesh_field(fig, ax, sx, sy, snap, plot):
    """A snapshot with cells (triangles): the field drawn on the mesh with tripcolor, flat per cell
    for a cell field (snapshot group cell_fields/), Gouraud-interpolated for a point field; the
    element edges thinly with `mesh = true` (colour `mesh_color`, default grey); velocity arrows interpolated on a regular grid with
    `arrows = [vx_field, vy_field]` (point fields; `arrow_grid` arrows across x, default 24)."""
    import matplotlib.tri as mtri
    from matplotlib.collections import LineCollection
    cells = snap["cells"][()].astype(np.int64)
    tri = mtri.Triangulation(sx, sy, cells)
    cf = snap["cell_fields"] if "cell_fields" in snap else {}
    field = plot.get("field")
    pc = None
    if field and field in snap and plot.get("center") != "cell":
        ds, on_cells = snap[field], False
    elif field and field in cf:
        ds, on_cells = cf[field], True
    else:
        ds = None
    if ds is not None:
        raw, unit = display_values(ds[()], _attr(ds, "units", "1"))
        # the colour range from what is drawn: the cells/nodes inside the window
        sample = None
        if plot.get("xlim") or plot.get("ylim"):
            px, py = (sx[cells].mean(axis=1), sy[cells].mean(axis=1)) if on_cells else (sx, sy)
            x0, x1 = plot.get("xlim", (-np.inf, np.inf))
            y0, y1 = plot.get("ylim", (-np.inf, np.inf))
            inside = (px >= x0) & (px <= x1) & (py >= y0) & (py <= y1)
            sample = raw[inside] if inside.any() else None
        norm, values, extend = field_norm(raw, plot, sample)
        cmap = plot.get("cmap", "viridis")
        if on_cells:
            pc = ax.tripcolor(tri, facecolors=values, norm=norm, cmap=cmap, shading="flat", edgecolors="none")
        else:
            pc = ax.tripcolor(tri, values, norm=norm, cmap=cmap, shading="gouraud")
        colour_bar(fig, ax, pc, extend, field_label(field, unit, plot))
    else:
        ax.triplot(tri, lw=0.2, color="0.5")
    if plot.get("mesh"):
        if "element" in cf:
            edges = element_edges(cells.tolist(), cf["element"][()])
        else:
            edges = {tuple(sorted(e)) for e in tri.edges.tolist()}
        segs = [((sx[a], sy[a]), (sx[b], sy[b])) for a, b in sorted(edges)]
        ax.add_collection(LineCollection(segs, colors=plot.get("mesh_color", "0.6"), linewidths=0.2, alpha=0.6))
    if plot.get("arrows"):
        fx, fy = plot["arrows"]
        if fx in snap and fy in snap:
            nx = int(plot.get("arrow_grid", 24))
            x0, x1 = plot.get("xlim", (sx.min(), sx.max()))  # the drawn window
            y0, y1 = plot.get("ylim", (sy.min(), sy.max()))
            ny = max(2, int(round(nx * (y1 - y0) / max(x1 - x0, 1e-300))))
            gx, gy = np.meshgrid(np.linspace(x0, x1, nx + 2)[1:-1], np.linspace(y0, y1, ny + 2)[1:-1])
            u = mtri.LinearTriInterpolator(tri, snap[fx][()])(gx, gy)
            v = mtri.LinearTriInterpolator(tri, snap[fy][()])(gx, gy)
            ax.quiver(gx, gy, u, v, color=plot.get("arrow_color", "w"), width=0.003, headwidth=3.5,
                      pivot="mid", zorder=3)
    ax.autoscale_view()
    return pc


def draw_particles(fig, ax, sx, sy, snap, plot):
    """A particle snapshot: squares (or F glyphs with `glyphs = "F"`) coloured by the field; tool
    particles (flag `rigid`) drawn apart in a flat colour with the tool outline and kept out of the
    colour range. Returns True when the tool was drawn."""
    field = plot.get("field")
    ds = snap[field] if field and field in snap else None
    n = len(sx)
    tool = None
    if "rigid" in snap:
        r = np.asarray(snap["rigid"][()], dtype=float)
        if r.shape == (n,) and (r > 0.5).any():
            tool = r > 0.5
    work = ~tool if tool is not None else np.ones(n, dtype=bool)
    norm = values = extend = label = None
    if ds is not None:
        raw, unit = display_values(ds[()], _attr(ds, "units", "1"))
        norm, values, extend = field_norm(raw, plot, raw[work])
        label = field_label(field, unit, plot)
    glyphs = plot.get("glyphs") == "F" and all(k in snap for k in ("F_xx", "F_xy", "F_yx", "F_yy"))
    F = np.stack([snap[k][()] for k in ("F_xx", "F_xy", "F_yx", "F_yy")], axis=1) if glyphs else None
    cmap = plot.get("cmap", "Greys")
    sel = work
    if glyphs:
        sc = draw_F_glyphs(ax, sx[sel], sy[sel], F[sel], None if values is None else values[sel], plot, norm)
        if tool is not None:
            draw_F_glyphs(ax, sx[tool], sy[tool], F[tool], None, plot, facecolor=TOOL_FACE, edgecolor=TOOL_EDGE)
    else:
        sc = ax.scatter(sx[sel], sy[sel], c=None if values is None else values[sel], norm=norm,
                        s=plot.get("size", 2), cmap=cmap, marker="s", linewidths=0)
        if tool is not None:
            ax.scatter(sx[tool], sy[tool], c=TOOL_FACE, s=plot.get("size", 2), marker="s", linewidths=0)
    if values is not None:
        colour_bar(fig, ax, sc, extend, label)
    return draw_tool(ax, snap, sx, sy, tool, axis_unit(plot.get("xlabel", ""), "mm"),
                     axis_unit(plot.get("ylabel", ""), "mm"))


def draw_plot(case, plot, root, outdir, h5path, tier_label):
    """Draw one [[plots]] entry from the HDF5 file `h5path` (None: only the paper's lines); the
    figure says which tier it shows (`tier_label`). Returns (png, svg, notes) or None."""
    fig, ax = plt.subplots(figsize=tuple(plot.get("figsize", (6.4, 4.2))), dpi=110)
    h5 = h5py.File(h5path, "r") if h5path else None
    drawn, computed, notes = 0, 0, []
    try:
        for line in plot.get("lines", []):
            style = dict(STYLES.get(line.get("style", "solid"), STYLES["solid"]))
            if "color" in line:
                style["color"] = line["color"]
            try:
                if "reference" in line:
                    x, y = ref_xy(root, case["paper"], line)
                    style.setdefault("color", "k")
                elif h5 is not None:
                    x, y = h5_xy(h5, line)
                    computed += 1
                else:
                    continue
            except KeyError:
                continue
            ax.plot(x, y, label=line.get("label"), **style)
            drawn += 1
        if plot.get("kind") == "snapshot" and h5 is not None:
            g = h5["series"][plot["series"]]["point_%d" % int(plot.get("run", 0))]["snapshots"]
            keys = sorted(g.keys(), key=int)
            snap = g[keys[int(plot.get("snapshot", -1))]]
            # snapshot positions are stored in metres; draw them in the unit named in the axis label
            sx = convert(snap["x"][()], "m", axis_unit(plot.get("xlabel", ""), "mm"))
            sy = convert(snap["y"][()], "m", axis_unit(plot.get("ylabel", ""), "mm"))
            ax.set_aspect("equal")  # before the colour bar: its axes follows the drawn one
            if "cells" in snap and plot.get("glyphs") != "F":
                draw_mesh_field(fig, ax, sx, sy, snap, plot)
            elif draw_particles(fig, ax, sx, sy, snap, plot):
                notes.append("tool outline drawn from its particles")
            ax.set_aspect("equal")
            drawn += 1
            computed += 1
    finally:
        if h5 is not None:
            h5.close()
    if drawn == 0:
        plt.close(fig)
        return None
    ax.set_xlabel(plot.get("xlabel", ""))
    ax.set_ylabel(plot.get("ylabel", ""))
    if plot.get("xscale"):
        ax.set_xscale(plot["xscale"])
    if plot.get("yscale"):
        ax.set_yscale(plot["yscale"])
    if plot.get("xlim"):
        ax.set_xlim(*plot["xlim"])
    if plot.get("ylim"):
        ax.set_ylim(*plot["ylim"])
    # long titles wrapped, not cut off at the figure edge
    # (the figure is saved with a tight bounding box: a title wider than a narrow equal-aspect
    # axes is not cut off)
    ax.set_title(textwrap.fill(plot.get("title", ""), int(plot.get("title_wrap", 62))), fontsize=9)
    ax.grid(True, alpha=0.3)
    if any(l.get("label") for l in plot.get("lines", [])):
        ax.legend(fontsize=7, loc=plot.get("legend", "best"))
    fig.tight_layout()
    # which tier the computed data come from, in the image itself (it may be looked at alone)
    label = tier_label if computed else "paper's data only (no computed data in this figure)"
    ax.annotate(label, xy=(0, 0), xycoords="axes fraction", xytext=(-30, -34), textcoords="offset points",
                fontsize=7.5, color=TIER_COLOUR.get(tier_label, "#1b3a6b"), style="italic", va="top", ha="left",
                annotation_clip=False)
    base = "%s_%s_%s" % (case["paper"], case["item_id"], plot.get("name", "plot"))
    png, svg = base + ".png", base + ".svg"
    # a tight bounding box: an equal-aspect snapshot axes is shrunk inside its slot (tight_layout
    # does not see it), and the tier line lies below the figure
    tight = {"bbox_inches": "tight", "pad_inches": 0.1}
    fig.savefig(os.path.join(outdir, "figures", png), metadata={"Software": None}, **tight)
    fig.savefig(os.path.join(outdir, "figures", svg), metadata={"Date": None, "Creator": None}, **tight)
    plt.close(fig)
    return png, svg, notes


def fmt(v):
    if v is None:
        return "—"
    if isinstance(v, list):
        return "[" + ", ".join(fmt(x) for x in v) + "]"
    if isinstance(v, float):
        if v == 0:
            return "0"
        if not math.isfinite(v):
            return html.escape(str(v))
        a = abs(v)
        return ("%.4g" % v) if 1e-3 <= a < 1e5 else ("%.3e" % v)
    return html.escape(str(v))


def esc(s):
    return html.escape(str(s if s is not None else ""))


# ----------------------------------------------------------------------------------------------
# verdicts: paper resolution (full-tier record or analytic evaluation) and regression (quick tier)

KINDS = ("verification", "reproduction", "validation", "consistency")
COUNTED = ("verification", "reproduction", "validation")  # consistency is shown apart, never counted
CHECK_STATUSES = ("PASS", "FAIL", "ERROR", "INCONCLUSIVE", "NOT RUN", "NOT IMPLEMENTED")
ITEM_STATUSES = ("PASS", "FAIL (known)", "FAIL", "ERROR", "INCONCLUSIVE", "NOT RUN", "NOT IMPLEMENTED",
                 "NOT YET RUN")
SHORT = {"INCONCLUSIVE": "INCONCL.", "NOT IMPLEMENTED": "NOT IMPL.", "NOT YET RUN": "NOT YET RUN"}
TIER_PAPER = "paper resolution (full tier, commit %s)"
TIER_QUICK = "regression run, quick tier, reduced resolution"
TIER_ANALYTIC = "analytic evaluation (closed form, the same at every tier)"
TIER_COLOUR = {TIER_QUICK: "#7a5b00"}


def known_text(ch, tier):
    """A check's known-failure text for `tier` (a table of tiers in case files, a string in records)."""
    kf = ch.get("known_failure")
    if isinstance(kf, dict):
        return kf.get(tier) or ""
    return kf or ""


def count_checks(checks):
    counts = {k: {} for k in KINDS}
    for ch in checks or []:
        d = counts.setdefault(ch.get("kind", "reproduction"), {})
        s = ch.get("status", "NOT RUN")
        d[s] = d.get(s, 0) + 1
    return counts


def commit_of(software):
    return software.split("+", 1)[1] if software and "+" in software else ""


def load_json(path):
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


class Verdict:
    """One tier's verdict on a case: status, basis, its check records (None when not at hand), the
    check counts by kind and status, and the number of failures no known_failure documents."""

    def __init__(self, v, checks, tier):
        self.v = v
        self.status = v.get("status") or "NOT RUN"
        self.basis = v.get("basis", "none")
        self.checks = checks
        self.tier = tier
        if checks is not None:
            self.counts = count_checks(checks)
            self.unexpected = sum(1 for ch in checks if ch.get("status") == "FAIL" and not known_text(ch, tier))
            self.known = {}
            for ch in checks:
                if ch.get("status") == "FAIL" and known_text(ch, tier):
                    k = ch.get("kind", "reproduction")
                    self.known[k] = self.known.get(k, 0) + 1
        else:
            self.counts = v.get("counts") or {k: {} for k in KINDS}
            self.unexpected = v.get("unexpected_failures")
            self.known = {}
        self.stale = bool(v.get("stale"))
        self.commit = v.get("commit") or commit_of(v.get("software", ""))

    @property
    def word(self):
        """The status as shown: a FAIL whose every failing check is documented is 'FAIL (known)'."""
        if self.status == "FAIL" and self.unexpected == 0:
            return "FAIL (known)"
        return self.status

    @property
    def has_verdict(self):
        return self.basis in ("full-tier record", "analytic evaluation") and self.status != "NOT YET RUN"

    def tally(self, kinds=COUNTED):
        """(passed, failed, known failed, other, total) over `kinds`."""
        p = f = o = 0
        for k in kinds:
            for s, n in (self.counts.get(k) or {}).items():
                if s == "PASS":
                    p += n
                elif s == "FAIL":
                    f += n
                else:
                    o += n
        return p, f, sum(self.known.get(k, 0) for k in kinds), o, p + f + o


def case_verdicts(c, root, full_records):
    """(paper resolution, regression) Verdicts of a manifest case. Manifests written before the
    binary gave verdicts are read as the binary reads them (a recorded full-tier run, else the
    analytic evaluation, else not yet run)."""
    last = c.get("last_run") or {}
    vs = c.get("verdicts") or {}
    pr = dict(vs.get("paper_resolution") or {})
    if not pr:
        rec = full_records.get(c["case"])
        if not c.get("implemented", True):
            pr = {"status": "NOT IMPLEMENTED", "basis": "none"}
        elif c.get("solver") == "analytic" and last:
            pr = {"status": last.get("status"), "basis": "analytic evaluation", "date": last.get("date", ""),
                  "software": last.get("software", "")}
        elif rec:
            pr = {"status": rec.get("status"), "basis": "full-tier record", "date": rec.get("date", ""),
                  "record": "reports/full_tier/%s.json" % c["case"], "software": rec.get("software", ""),
                  "how": (rec.get("recorded") or {}).get("how", "")}
            if "unexpected_failures" in rec:
                pr["unexpected_failures"] = rec["unexpected_failures"]
        else:
            pr = {"status": "NOT YET RUN", "basis": "none"}
    pr_checks, pr_tier = None, "full"
    if pr.get("basis") == "full-tier record":
        rec = load_json(os.path.join(root, pr["record"])) if pr.get("record") else None
        rec = rec or full_records.get(c["case"])
        pr_checks = (rec or {}).get("checks")
        pr.setdefault("threads", (rec or {}).get("threads"))
        pr.setdefault("notes", (rec or {}).get("notes") or [])
    elif pr.get("basis") == "analytic evaluation":
        pr_checks, pr_tier = last.get("checks"), last.get("tier", "quick")
    rg = dict(vs.get("regression") or {})
    if not rg:
        rg = {"status": last.get("status", "NOT RUN") if last else
              ("NOT RUN" if c.get("implemented", True) else "NOT IMPLEMENTED"),
              "basis": "quick tier (reduced resolution)" if last else "none", "tier": last.get("tier", "quick"),
              "date": last.get("date", ""), "software": last.get("software", "")}
    rg_checks = last.get("checks") if last else None
    if pr_checks and rg_checks:
        # records made before checks carried `finding`/`tolerance_source` take them from the same
        # check of this results directory (which the current case file made)
        spec = {ch.get("key"): ch for ch in rg_checks}
        filled = []
        for ch in pr_checks:
            q = spec.get(ch.get("key")) or {}
            add = {k: q[k] for k in ("finding", "tolerance_source") if q.get(k) and not ch.get(k)}
            filled.append(dict(ch, **add) if add else ch)
        pr_checks = filled
    return Verdict(pr, pr_checks, pr_tier), Verdict(rg, rg_checks, last.get("tier", "quick"))


# ----------------------------------------------------------------------------------------------
# HTML

def badge(status, title=None, text=None):
    t = ' title="%s"' % esc(title) if title else ""
    return '<span class="badge %s"%s>%s</span>' % (STATUS_CLASS.get(status, "notrun"), t, esc(text or status))


def stale_tag(v):
    if not v.stale:
        return ""
    return ' <span class="stale" title="%s">stale · %s</span>' % (
        esc(v.v.get("stale_reason", "made by other solver sources than this build's")), esc(v.commit or "?"))


def finding_link(paper, fid, findings):
    """'F03' linked to the paper's findings page (plain, and marked, when the paper has none or
    the page lacks that id)."""
    ids = findings.get(paper)
    if ids is None:
        return '<span class="fid" title="no FINDINGS.md for %s">%s</span>' % (esc(paper), esc(fid))
    missing = fid not in ids
    return '<a class="fid%s" href="findings-%s.html#%s"%s>%s</a>' % (
        " missing" if missing else "", esc(paper), esc(fid),
        ' title="not in FINDINGS.md"' if missing else "", esc(fid))


def tally_cell(v, kinds=COUNTED):
    """'12/14 pass · 2 FAIL (2 known)' for the checks of `kinds` ('—' without any)."""
    p, f, kf, o, n = v.tally(kinds)
    if n == 0:
        return '<span class="small">—</span>'
    parts = ['<span class="n%s">%d/%d passed</span>' % (" allpass" if p == n else "", p, n)]
    if f:
        parts.append('<span class="nfail%s">%d FAIL%s</span>' % (
            " nknown" if kf == f else "", f, (" (%d known)" % kf) if kf else ""))
    for s in ("ERROR", "INCONCLUSIVE", "NOT RUN", "NOT IMPLEMENTED"):
        m = sum((v.counts.get(k) or {}).get(s, 0) for k in kinds)
        if m:
            parts.append('<span class="n%s">%d %s</span>' % (STATUS_CLASS.get(s, ""), m, esc(SHORT.get(s, s))))
    return "<br>".join(parts)


def check_status_cell(ch, paper, tier, findings):
    s = ch.get("status", "NOT RUN")
    known = known_text(ch, tier)
    out = [badge("FAIL (known)" if s == "FAIL" and known else s)]
    if ch.get("audit"):
        out.append(' <span class="audit" title="%s">⚑ cannot fail</span>' % esc(ch["audit"]))
    if s == "FAIL" and known:
        out.append('<div class="known">known: %s%s</div>' % (
            esc(known), (" — " + finding_link(paper, ch["finding"], findings)) if ch.get("finding") else ""))
    elif known and s != "FAIL":
        out.append('<div class="small">documented as a known failure in this tier, but %s: %s</div>' % (
            esc(s), esc(known)))
    if s == "INCONCLUSIVE":
        sc = ch.get("scatter")
        out.append('<div class="inconcl-msg">%s%s</div>' % (
            esc(ch.get("message", "")),
            ('<br>scatter ± %s%s%s' % (fmt(sc), "" if isinstance(sc, str) else " " + esc(ch.get("units", "")),
                                        (" (" + esc(ch.get("scatter_source", "")) + ")")
                                        if ch.get("scatter_source") else "")) if sc is not None else ""))
    elif ch.get("message"):
        out.append('<div class="%s">%s</div>' % ("error-msg" if s == "ERROR" else "small", esc(ch["message"])))
    if ch.get("audit"):
        out.append('<div class="small">audit: %s</div>' % esc(ch["audit"]))
    return "".join(out)


def checks_table(checks, paper, tier, findings):
    """The tables of check records (paper | cutbench | error | tolerance | status | source): the
    verification/reproduction/validation checks, then the consistency checks apart."""
    main = [ch for ch in checks if ch.get("kind") != "consistency"]
    cons = [ch for ch in checks if ch.get("kind") == "consistency"]
    out = []
    for rows, caption in ((main, ""), (cons, "Consistency checks (our model against itself; they cannot test "
                                             "the paper's claim and are not counted as reproduction or "
                                             "validation)")):
        if not rows:
            continue
        t = ['<table class="checks%s">' % (" consistency" if caption else "")]
        if caption:
            t.append('<caption>%s</caption>' % esc(caption))
        t.append("<tr><th>check</th><th>kind</th><th>paper / reference</th><th>cutbench</th><th>error</th>"
                 "<th>tolerance</th><th>units</th><th>status</th><th>source</th></tr>")
        for ch in rows:
            tol = ch.get("tolerance")
            tol_s = "range" if ch.get("tolerance_type") == "range" else (
                ("%s rel" % fmt(tol)) if ch.get("tolerance_type") == "relative" else fmt(tol))
            s = ch.get("status", "NOT RUN")
            cls = {"FAIL": "known" if known_text(ch, tier) else "fail", "ERROR": "error",
                   "INCONCLUSIVE": "inconcl"}.get(s, "")
            src = [esc(ch.get("source", ""))]
            if ch.get("tolerance_source"):
                src.append('<br><i>tolerance:</i> %s' % esc(ch["tolerance_source"]))
            if ch.get("finding") and not (s == "FAIL" and known_text(ch, tier)):
                src.append('<br><i>finding:</i> %s' % finding_link(paper, ch["finding"], findings))
            t.append('<tr class="row-%s"><td><code>%s</code>%s</td><td>%s</td><td>%s</td><td>%s</td><td>%s</td>'
                     '<td>%s</td><td>%s</td><td>%s</td><td class="small">%s</td></tr>' % (
                         cls, esc(ch.get("key", "?")),
                         ('<br><span class="small">%s</span>' % esc(ch["description"])) if ch.get("description") else "",
                         esc(ch.get("kind", "")), fmt(ch.get("reference")), fmt(ch.get("value")),
                         fmt(ch.get("error")), tol_s, esc(ch.get("units", "")),
                         check_status_cell(ch, paper, tier, findings), "".join(src)))
        t.append("</table>")
        out.append("".join(t))
    return "".join(out)


def first_sentence(text, limit=200):
    """The first sentence of a requirement (not cut at 'Fig.', 'Eq.', 'e.g.' and the like)."""
    text = " ".join((text or "").split())
    m = re.search(r"(?<!\bFig)(?<!\bFigs)(?<!\bEq)(?<!\bEqs)(?<!\bSec)(?<!\bRef)(?<!\bvs)(?<!\bNo)"
                  r"(?<!\be\.g)(?<!\bi\.e)(?<!\bal)(?<!\bapprox)[.](\s+(?=[A-Z(])|$)", text)
    s = text[:m.start() + 1] if m else text
    if len(s) > limit:
        s = s[:limit - 1].rsplit(" ", 1)[0] + "…"
    return s


def counts_line(counts):
    """'PASS 19 · FAIL (known) 23 · ...' of item statuses."""
    return " · ".join('%s <b class="cnt">%d</b>' % (badge(s), counts[s]) for s in ITEM_STATUSES if counts.get(s))


def case_claim(c):
    return c.get("claim") or first_sentence(c.get("requirement", ""))


CSS = """
body{font-family:system-ui,-apple-system,'Segoe UI',sans-serif;margin:0;color:#1d2330;background:#f6f7f9}
header{background:#1d2330;color:#fff;padding:14px 28px}header a{color:#cfe3ff}
main{padding:18px 28px;max-width:1280px}
h1{font-size:22px;margin:0}h2{font-size:18px;border-bottom:1px solid #d5d9e0;padding-bottom:4px}
h3{font-size:15px;margin:0 0 6px}h4{font-size:14px;margin:10px 0 4px}
table{border-collapse:collapse;font-size:13px;margin:8px 0;background:#fff}
td,th{border:1px solid #d5d9e0;padding:4px 8px;text-align:left;vertical-align:top}
table.checks,table.index,table.items{width:100%}table.checks td:nth-child(8){min-width:230px}
table.checks td:nth-child(9){min-width:200px}table.items td:first-child{white-space:nowrap}
.md table{display:block;overflow-x:auto;max-width:100%}.cnt{margin-right:4px}
table.index td.num{width:1%;white-space:nowrap}table.index th.num{width:1%}
.n,.nfail,.nerror,.ninconcl,.nnotrun,.nni{white-space:nowrap}
th{background:#eef1f5}td.num,th.num{text-align:right}
caption{text-align:left;font-size:12px;color:#4a4f5c;padding:4px 0;caption-side:top}
.badge{display:inline-block;padding:1px 7px;border-radius:9px;font-size:12px;font-weight:600;white-space:nowrap}
.pass{background:#d8f3dc;color:#1b5e20}.fail{background:#ffd6d6;color:#8b0000}
.known{background:#ffe8cc;color:#7a3e00}.error{background:#8b0000;color:#fff}
.inconcl{background:#e8ddff;color:#4b2a8a}.notrun{background:#fff1c1;color:#7a5b00}
.ni{background:#e4e6eb;color:#4a4f5c}.nyr{background:#fff;color:#5b6272;border:1px dashed #9aa1ad}
div.known{background:none;font-size:12px;margin-top:2px}
.stale{display:inline-block;font-size:11px;padding:0 6px;border:1px solid #d4a100;background:#fff6d6;
 color:#6b4f00;border-radius:4px;white-space:nowrap}
.audit{font-size:11px;padding:0 5px;border:1px solid #7f9cc7;background:#eef4ff;color:#1f3f75;
 border-radius:4px;white-space:nowrap}
.fid{font-weight:600}.fid.missing{color:#8b0000;text-decoration:line-through}
.case{background:#fff;border:1px solid #d5d9e0;border-radius:6px;padding:12px 16px;margin:14px 0}
.verdict{border-left:4px solid #1d2330;padding:2px 0 2px 10px;margin:8px 0}
.regression{border-left:4px solid #d4a100;padding:2px 0 2px 10px;margin:12px 0;color:#333}
.regression summary{cursor:pointer;font-size:14px}
.figs img{max-width:100%;width:auto;height:auto;border:1px solid #e1e4ea;margin:4px 8px 0 0}
.figs figure{display:inline-block;margin:0 8px 8px 0;vertical-align:top;max-width:560px}
figcaption{font-size:11px;font-style:italic}
.tier-paper{color:#1b3a6b}.tier-quick{color:#7a5b00}
.small{font-size:12px;color:#5b6272}.note{font-size:12px;color:#7a3e00}
.claim{font-size:14px;margin:4px 0}
.inconcl-msg{font-size:12px;color:#4b2a8a}.error-msg{font-size:12px;color:#8b0000;font-weight:600}
.n{font-weight:600}.allpass{color:#1b5e20}.nfail{color:#8b0000;font-weight:600}.nknown{color:#7a3e00}
.nerror{color:#fff;background:#8b0000;padding:0 3px;border-radius:3px}.ninconcl{color:#4b2a8a}
.nnotrun{color:#7a5b00}.nni{color:#4a4f5c}
tr.row-fail td:first-child{border-left:4px solid #c62828}tr.row-error td:first-child{border-left:4px solid #5a0000}
tr.row-known td:first-child{border-left:4px solid #e0a060}tr.row-inconcl td:first-child{border-left:4px solid #7e57c2}
table.consistency{opacity:.92}table.consistency th{background:#f3f0f7}
.regtable{font-size:12px;color:#4a4f5c}.regtable th{background:#f6f7f9;font-weight:500}
.headline{font-size:15px;margin:6px 0 4px}.headline b{font-size:17px}
.legend{font-size:12px;color:#4a4f5c;margin:10px 0}.legend .badge{margin-right:2px}
.md h3{font-size:15px;border-top:1px solid #d5d9e0;padding-top:10px;margin-top:18px}
.md li{margin:2px 0}.md{background:#fff;border:1px solid #d5d9e0;border-radius:6px;padding:4px 20px 12px}
.citedby{font-size:12px;color:#4a4f5c;margin:-2px 0 6px}
code{font-size:12px;background:#f1f3f6;padding:0 3px;border-radius:3px}
"""

LEGEND = ('<p class="legend">%s every check passed · %s a check failed and every failing check is a documented '
          'known failure (with its finding) · %s a check failed that no known failure documents · %s a solver '
          'series threw, produced a non-finite output or tripped a blow-up guard · %s the value lies within the '
          'measured run-to-run scatter of a pass/fail boundary · %s the paper gives no value, or the model does '
          'not apply · %s no model or solver yet · %s no paper-resolution record yet (the regression column is the '
          'reduced-resolution quick tier) · <span class="stale">stale</span> the record was made by other solver '
          'sources than this build\'s · <span class="audit">⚑ cannot fail</span> the check\'s audit found it '
          'cannot fail.</p>') % tuple(badge(s) for s in ITEM_STATUSES)


def page(title, body, root_rel=""):
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>%s</title>"
            "<style>%s</style></head><body><header><h1><a href=\"%sindex.html\">cutbench</a> — %s</h1>"
            "</header><main>%s</main></body></html>\n") % (html.escape(title), CSS, root_rel,
                                                           html.escape(title), body)


def write(path, text):
    tmp = path + ".tmp"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(tmp, path)


def load_full_records(directory):
    """Recorded full-tier case records (reports/full_tier/<paper>/<item>.json), by case id."""
    out = {}
    if not os.path.isdir(directory):
        return out
    for paper in sorted(os.listdir(directory)):
        pdir = os.path.join(directory, paper)
        if not os.path.isdir(pdir):
            continue
        for name in sorted(os.listdir(pdir)):
            if name.endswith(".json"):
                rec = load_json(os.path.join(pdir, name))
                if isinstance(rec, dict) and rec.get("case"):
                    out[rec["case"]] = rec
    return out


def runs_summary(fr):
    """'3 of 30 (1 running, 1 with a checkpoint)' for the stored full-tier solver runs ('-' without any)."""
    if not fr or not fr.get("total"):
        return "-"
    parts = []
    if fr.get("running"):
        parts.append("%d running" % fr["running"])
    if fr.get("checkpoint"):
        parts.append("%d with a checkpoint" % fr["checkpoint"])
    extra = " (%s)" % ", ".join(parts) if parts else ""
    return "%d of %d%s" % (fr.get("stored", 0), fr["total"], extra)


def runs_in_progress(fr):
    """'mpm_cutting-....run running, 62 % done; ...' for the runs under way ('' when none)."""
    out = []
    for r in (fr or {}).get("in_progress", []):
        f = r.get("fraction_done", -1)
        out.append("%s %s%s" % (r["file"], r["state"], ", %d %% done" % int(100 * f) if f is not None and f >= 0 else ""))
    return "; ".join(out)


def tier_label_of(pr, rg, c):
    """(h5 path, label, css class) of the data a case's plots are drawn from: the paper-resolution
    record's HDF5 where it exists, else this results directory's (the quick-tier regression run)."""
    h5 = pr.v.get("h5")
    if h5 and os.path.exists(h5):
        return h5, TIER_PAPER % (pr.commit or "?"), "tier-paper"
    if c.get("h5"):
        tier = (c.get("last_run") or {}).get("tier", "quick")
        if pr.basis == "analytic evaluation":
            return c["h5"], TIER_ANALYTIC, "tier-paper"
        if tier == "quick":
            return c["h5"], TIER_QUICK, "tier-quick"
        return c["h5"], "run in this results directory, %s tier" % tier, "tier-quick"
    return None, TIER_QUICK, "tier-quick"


def verdict_block(c, pr, findings):
    """The paper-resolution verdict of a case: status, where it comes from, its checks."""
    paper = c["paper"]
    out = ['<div class="verdict"><h4>Paper resolution: %s%s</h4>' % (badge(pr.word), stale_tag(pr))]
    v = pr.v
    if pr.basis == "full-tier record":
        out.append('<p class="small">From the recorded full-tier run <code>%s</code> · commit %s · run %s%s.</p>' % (
            esc(v.get("record", "")), esc(pr.commit or "?"), esc(v.get("date", "")),
            (" · %s thread(s)" % esc(v["threads"])) if v.get("threads") else ""))
        if pr.stale:
            out.append('<p class="note">Stale: %s. The verdict stands for the sources that made it; a new '
                       'full-tier run is needed to confirm it with this build.</p>' % esc(v.get("stale_reason", "")))
        if v.get("how"):
            out.append('<details class="small"><summary>how it was run</summary><p>%s</p></details>' % esc(v["how"]))
    elif pr.basis == "analytic evaluation":
        out.append('<p class="small">Analytic evaluation: closed-form, the same at every tier (evaluated %s, '
                   'software %s).</p>' % (esc(v.get("date", "")), esc(v.get("software", ""))))
    elif pr.status == "NOT YET RUN":
        out.append('<p class="note">Not yet run at paper resolution: no full-tier record. Only the regression '
                   'run (quick tier, reduced resolution) below has evaluated this case.</p>')
    elif pr.status == "NOT IMPLEMENTED":
        out.append('<p class="note">Not implemented: %s</p>' % esc(c.get("reason", "")))
    if v.get("message"):
        out.append('<p class="error-msg">%s</p>' % esc(v["message"]))
    if pr.checks:
        table = checks_table(pr.checks, paper, pr.tier, findings)
        if len(pr.checks) > 8 and all(ch.get("status") == "PASS" and not ch.get("audit") for ch in pr.checks):
            table = '<details><summary>%d checks, all passed (show)</summary>%s</details>' % (len(pr.checks), table)
        out.append(table)
    out.append("</div>")
    return "".join(out)


def regression_block(c, rg, findings, open_):
    """The quick-tier (reduced resolution) checks of a case, below the paper-resolution verdict."""
    last = c.get("last_run") or {}
    if not rg.checks:
        if rg.status in ("NOT IMPLEMENTED",):
            return ""
        return ('<div class="regression"><span class="small">Regression run (quick tier, reduced resolution): '
                '%s — no checks in this results directory.</span></div>' % badge(rg.word))
    tier = last.get("tier", "quick")
    what = ("Regression run — quick tier, reduced resolution" if tier == "quick"
            else "Run in this results directory — %s tier" % esc(tier))
    return ('<details class="regression"%s><summary><b>%s</b>: %s · %s · <span class="small">run %s, '
            '%.2f s</span></summary>%s</details>') % (
        " open" if open_ else "", what, badge(rg.word), tally_cell(rg), esc(last.get("date", "")),
        last.get("wall_time_s", 0) or 0, checks_table(rg.checks, c["paper"], rg.tier, findings))


def case_section(c, pr, rg, root, out_dir, findings):
    """One case: paper-resolution verdict and checks first, then figures, then the regression run."""
    last = c.get("last_run") or {}
    parts = []
    figs = []
    h5path, label, tcls = tier_label_of(pr, rg, c)
    if h5path or any(all("reference" in l for l in p.get("lines", [])) for p in c.get("plots", [])):
        for p in c.get("plots", []):
            try:
                r = draw_plot(c, p, root, out_dir, h5path, label)
            except Exception as e:  # a broken plot must not hide the rest of the report
                parts.append('<p class="note">Plot %s failed: %s</p>' % (esc(p.get("name", "")), esc(e)))
                continue
            if r:
                # the tier is written in the image itself, below the axes
                figs.append('<figure><a href="figures/%s"><img src="figures/%s" alt="%s (%s)"></a>%s</figure>' % (
                    r[1], r[0], esc(p.get("title", "")), esc(label),
                    '<figcaption class="%s">%s</figcaption>' % (tcls, esc("; ".join(r[2]))) if r[2] else ""))
    head = ['<div class="case" id="%s" data-plots="%d"><h3>%s — %s %s%s</h3>' % (
        esc(c["item_id"]), len(figs), esc(c.get("item", c["item_id"])), esc(c.get("title", "")),
        badge(pr.word), stale_tag(pr))]
    head.append('<p class="claim"><b>Claim:</b> %s</p>' % esc(case_claim(c)))
    if c.get("requirement") and c.get("claim"):
        head.append('<p class="small"><b>Requirement:</b> %s</p>' % esc(c["requirement"]))
    head.append('<p class="small">case <code>%s</code> · solver %s · models %s · tiers %s</p>' % (
        esc(c["case"]), esc(c.get("solver", "")), esc(", ".join(c.get("models", []))),
        esc(", ".join(c.get("tiers", [])))))
    head.append(verdict_block(c, pr, findings))
    if figs:
        head.append('<div class="figs">%s</div>' % "".join(figs))
    head.extend(parts)
    head.append(regression_block(c, rg, findings, open_=not pr.checks))
    if c.get("assumptions"):
        head.append('<div class="note"><b>Assumptions</b><ul>%s</ul></div>' % "".join(
            "<li>%s</li>" % esc(asm) for asm in c["assumptions"]))
    notes = [("regression run", n) for n in last.get("notes", [])]
    notes += [("paper resolution", n) for n in pr.v.get("notes", []) if pr.basis == "full-tier record"]
    if notes:
        head.append('<details class="small"><summary>run notes (%d)</summary><ul>%s</ul></details>' % (
            len(notes), "".join("<li><i>%s:</i> %s</li>" % (esc(t), esc(n)) for t, n in notes)))
    fr = c.get("full_runs")
    if fr:
        under_way = runs_in_progress(fr)
        head.append('<p class="small">Full-tier campaign: %s solver runs stored in '
                    '<code>reports/full_tier/runs</code>%s (<code>cutbench runs --case %s</code>).</p>' % (
                        esc(runs_summary(fr)), "; under way: " + esc(under_way) if under_way else "",
                        esc(c["case"])))
    head.append("</div>")
    return "".join(head)


def items_table(cases, verdicts, paper, findings):
    """The paper page's opening table: one row per item."""
    rows = ['<table class="items"><tr><th>item</th><th>the paper\'s claim</th><th>paper resolution</th>'
            '<th>regression<br><span class="small">quick tier, reduced resolution</span></th>'
            '<th>checks at paper resolution<br><span class="small">verification + reproduction + validation: '
            'passed/total</span></th><th>consistency<br><span class="small">apart, not counted</span></th></tr>']
    for c in cases:
        pr, rg = verdicts[c["case"]]
        extra = ""
        if pr.status == "NOT YET RUN":
            extra = '<br><span class="small">not yet run at paper resolution</span>'
        elif pr.basis == "analytic evaluation":
            extra = '<br><span class="small">analytic (any tier)</span>'
        rows.append('<tr><td><a href="#%s">%s</a></td><td>%s</td><td>%s%s%s</td><td>%s</td><td>%s</td>'
                    '<td>%s</td></tr>' % (
                        esc(c["item_id"]), esc(c.get("item", c["item_id"])), esc(case_claim(c)), badge(pr.word),
                        stale_tag(pr), extra, badge(rg.word), tally_cell(pr), tally_cell(pr, ("consistency",))))
    rows.append("</table>")
    return "".join(rows)


def findings_page(paper, path, cites, out_dir):
    """findings-<paper>.html: the paper's FINDINGS.md, each finding with the checks that cite it."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    ids = report_md.finding_ids(text)

    def after(fid):
        refs = cites.get(fid)
        if not refs:
            return '<p class="citedby">Cited by no check in this report.</p>'
        return '<p class="citedby">Cited by: %s</p>' % ", ".join(
            '<a href="%s.html#%s">%s</a> <code>%s</code> (%s)' % (esc(paper), esc(item), esc(item), esc(key), esc(what))
            for item, key, what in refs)
    body = ('<p><a href="%s.html">← %s</a> · the evidence behind the known failures, tolerances and '
            'assumptions of its cases (<code>benchmarks/%s/FINDINGS.md</code>).</p><div class="md">%s</div>') % (
        esc(paper), esc(paper), esc(paper), report_md.to_html(text, ids, after))
    write(os.path.join(out_dir, "findings-%s.html" % paper), page("%s: findings" % paper, body))
    return ids


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--root", required=True)
    ap.add_argument("--results", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--full-tier", default=None,
                    help="recorded full-tier runs (default <root>/reports/full_tier); read where the manifest "
                         "gives no verdicts")
    a = ap.parse_args()
    full_records = load_full_records(a.full_tier or os.path.join(a.root, "reports", "full_tier"))
    with open(os.path.join(a.results, "manifest.json"), encoding="utf-8") as f:
        man = json.load(f)
    os.makedirs(os.path.join(a.out, "figures"), exist_ok=True)
    papers = dict(man.get("papers") or {})
    by_paper = {}
    for c in man.get("cases", []):
        by_paper.setdefault(c["paper"], []).append(c)
        papers.setdefault(c["paper"], {"meta": {}, "items": []})
    # cases in the paper's inventory order (tables and figures as the paper numbers them)
    for pid, cases in by_paper.items():
        order = {it.get("id"): i for i, it in enumerate(papers[pid].get("items") or [])}
        cases.sort(key=lambda c: (order.get(c["item_id"], len(order)), c["item_id"]))
    verdicts = {c["case"]: case_verdicts(c, a.root, full_records) for cs in by_paper.values() for c in cs}

    # findings pages first: the check tables link into them
    findings, cites = {}, {}
    for pid, cases in by_paper.items():
        refs = {}
        for c in cases:
            pr, rg = verdicts[c["case"]]
            for v, what in ((pr, "paper resolution"), (rg, "regression")):
                for ch in v.checks or []:
                    if ch.get("finding"):
                        w = what + (", known failure" if ch.get("status") == "FAIL" and known_text(ch, v.tier) else "")
                        lst = refs.setdefault(ch["finding"], [])
                        if not any(r[:2] == (c["item_id"], ch.get("key", "")) for r in lst):
                            lst.append((c["item_id"], ch.get("key", ""), w))
        cites[pid] = refs
    for pid in papers:
        path = papers[pid].get("findings")
        if path and os.path.exists(path):
            try:
                findings[pid] = findings_page(pid, path, cites.get(pid, {}), a.out)
            except (OSError, UnicodeDecodeError) as e:
                print("report: %s: %s" % (path, e), file=sys.stderr)

    index_rows, reg_rows = [], []
    total = {"items": 0, "verdict": 0, "stale": 0, "nyr": 0, "pr": {}, "rg": {}, "checks": None}
    for pid in papers:
        cases = by_paper.get(pid, [])
        meta = papers[pid].get("meta", {}) or {}
        pr_counts, rg_counts = {}, {}
        n_verdict = n_stale = n_nyr = 0
        for c in cases:
            pr, rg = verdicts[c["case"]]
            pr_counts[pr.word] = pr_counts.get(pr.word, 0) + 1
            rg_counts[rg.word] = rg_counts.get(rg.word, 0) + 1
            n_verdict += pr.has_verdict
            n_stale += pr.has_verdict and pr.stale
            n_nyr += pr.status == "NOT YET RUN"
        # the paper page: one table of items, then the cases
        body = ["<p>%s<br><span class=\"small\">DOI: %s%s</span></p>" % (
            esc(meta.get("citation", pid)), esc(meta.get("doi", "unknown")),
            (" · not covered: " + esc(meta["skipped"])) if meta.get("skipped") else "")]
        if pid in findings:
            body.append('<p>Findings (evidence behind known failures and tolerances): '
                        '<a href="findings-%s.html">findings-%s</a></p>' % (esc(pid), esc(pid)))
        body.append('<p class="headline">Paper resolution: <b>%d</b> of %d items with a verdict (%d stale), '
                    '<b>%d</b> not yet run at paper resolution · %s</p>' % (
                        n_verdict, len(cases), n_stale, n_nyr,
                        counts_line(pr_counts)))
        body.append(items_table(cases, verdicts, pid, findings))
        body.append(LEGEND)
        for c in cases:
            pr, rg = verdicts[c["case"]]
            body.append(case_section(c, pr, rg, a.root, a.out, findings))
        write(os.path.join(a.out, pid + ".html"), page(pid, "".join(body)))

        agg = Verdict({}, [], "full")
        agg.counts = {k: {} for k in KINDS}
        for c in cases:
            pr = verdicts[c["case"]][0]
            for k, d in pr.counts.items():
                for s, n in d.items():
                    agg.counts.setdefault(k, {})[s] = agg.counts.setdefault(k, {}).get(s, 0) + n
            for k, n in pr.known.items():
                agg.known[k] = agg.known.get(k, 0) + n
        index_rows.append((pid, meta, len(cases), pr_counts, n_verdict, n_stale, n_nyr, agg))
        reg_rows.append((pid, rg_counts, man.get("full_runs", {}).get(pid)))
        total["items"] += len(cases)
        total["verdict"] += n_verdict
        total["stale"] += n_stale
        total["nyr"] += n_nyr
        for s, n in pr_counts.items():
            total["pr"][s] = total["pr"].get(s, 0) + n
        for s, n in rg_counts.items():
            total["rg"][s] = total["rg"].get(s, 0) + n
        if total["checks"] is None:
            total["checks"] = Verdict({}, [], "full")
        for k, d in agg.counts.items():
            for s, n in d.items():
                total["checks"].counts.setdefault(k, {})[s] = total["checks"].counts.setdefault(k, {}).get(s, 0) + n
        for k, n in agg.known.items():
            total["checks"].known[k] = total["checks"].known.get(k, 0) + n
    tot_checks = total["checks"] or Verdict({}, [], "full")

    # the index: one table of papers, paper-resolution numbers; regression numbers apart, smaller
    # status columns: PASS, FAIL (known), FAIL and ERROR always (a 0 there says something); the others
    # where some item has them
    shown = [s for s in ITEM_STATUSES if s in ("PASS", "FAIL (known)", "FAIL", "ERROR") or
             (s != "NOT YET RUN" and total["pr"].get(s))]
    head = ("<tr><th rowspan=2>paper</th><th rowspan=2 class=num>items</th>"
            "<th colspan=%d>items by paper-resolution verdict</th><th rowspan=2 class=num>with a verdict<br>"
            "<span class=small>(stale)</span></th><th rowspan=2 class=num>not yet run at paper resolution</th>"
            "<th colspan=3>checks at paper resolution: passed/total</th><th rowspan=2>consistency<br>"
            "<span class=small>apart, not counted</span></th></tr><tr>%s<th>verification</th><th>reproduction</th>"
            "<th>validation</th></tr>") % (
        len(shown), "".join("<th class=num>%s</th>" % badge(s, text=SHORT.get(s, s)) for s in shown))

    def row(name, n, counts, nv, ns, nn, agg, bold=False):
        td = "th" if bold else "td"
        cells = "".join('<%s class=num>%s</%s>' % (td, counts.get(s, 0) or '<span class="small">0</span>', td)
                        for s in shown)
        return ("<tr><%s>%s</%s><%s class=num>%d</%s>%s<%s class=num>%d%s</%s><%s class=num>%d</%s>"
                "<%s>%s</%s><%s>%s</%s><%s>%s</%s><%s>%s</%s></tr>") % (
            td, name, td, td, n, td, cells, td, nv, (' <span class="small">(%d)</span>' % ns), td, td, nn, td,
            td, tally_cell(agg, ("verification",)), td, td, tally_cell(agg, ("reproduction",)), td,
            td, tally_cell(agg, ("validation",)), td, td, tally_cell(agg, ("consistency",)), td)
    rows = []
    for pid, meta, n, counts, nv, ns, nn, agg in index_rows:
        name = '<a href="%s.html" title="%s"><b>%s</b></a>%s' % (
            esc(pid), esc(meta.get("citation", "")), esc(pid),
            ('<br><a class="small" href="findings-%s.html">findings</a>' % esc(pid)) if pid in findings else "")
        rows.append(row(name, n, counts, nv, ns, nn, agg))
    rows.append(row("all", total["items"], total["pr"], total["verdict"], total["stale"], total["nyr"],
                    tot_checks, bold=True))
    pr_line = counts_line(total["pr"])
    p, f, kf, o, nchk = tot_checks.tally()
    body = ['<p class="headline">Paper resolution: <b>%d</b> of %d items have a verdict (%d of them stale), '
            '<b>%d</b> not yet run at paper resolution · %s</p>' % (
                total["verdict"], total["items"], total["stale"], total["nyr"], pr_line),
            '<p class="small">Paper resolution = the recorded full-tier run of a case '
            '(<code>reports/full_tier/&lt;paper&gt;/&lt;item&gt;.json</code>, CPU-hours, not part of the main job), '
            'or its analytic evaluation (closed form, the same at every tier). Checks at paper resolution: '
            '%d of %d passed, %d failed (%d of them documented known failures); consistency checks apart.</p>' % (
                p, nchk, f, kf),
            "<table class=\"index\">%s%s</table>" % (head, "".join(rows)), LEGEND]
    # regression (quick tier): smaller, labelled
    rhead = "".join("<th class=num>%s</th>" % esc(s) for s in ITEM_STATUSES if s != "NOT YET RUN")
    rrows = []
    for pid, counts, fr in reg_rows:
        rrows.append("<tr><td>%s</td>%s<td>%s</td></tr>" % (
            esc(pid), "".join("<td class=num>%d</td>" % counts.get(s, 0) for s in ITEM_STATUSES
                              if s != "NOT YET RUN"), runs_summary(fr)))
    rrows.append("<tr><th>all</th>%s<th>%s</th></tr>" % (
        "".join("<th class=num>%d</th>" % total["rg"].get(s, 0) for s in ITEM_STATUSES if s != "NOT YET RUN"),
        runs_summary({k: sum((fr or {}).get(k, 0) for _, _, fr in reg_rows)
                      for k in ("total", "stored", "checkpoint", "running")})))
    body.append('<h2 class="small">Regression, reduced resolution (quick tier, this results directory)</h2>'
                '<p class="small">The quick tier runs every case at reduced resolution in the main job to catch '
                'regressions; its statuses are not the paper-resolution verdicts above. Software %s · manifest '
                'written %s. Last column: the distinct solver runs the full-tier cases need and how many the '
                'repository keeps (<code>reports/full_tier/runs</code>; <code>cutbench runs --paper P</code>).</p>'
                '<table class="regtable"><tr><th>paper</th>%s<th>full tier, stored solver runs</th></tr>%s</table>'
                % (esc(man.get("software", "")), esc(man.get("date", "")), rhead, "".join(rrows)))
    write(os.path.join(a.out, "index.html"), page("summary", "".join(body)))
    print("report: %d cases; paper resolution: %d with a verdict (%d stale), %d not yet run, %s; "
          "regression (quick tier): %s" % (
              total["items"], total["verdict"], total["stale"], total["nyr"],
              {s: total["pr"][s] for s in ITEM_STATUSES if total["pr"].get(s)},
              {s: total["rg"][s] for s in ITEM_STATUSES if total["rg"].get(s)}))


if __name__ == "__main__":
    main()
