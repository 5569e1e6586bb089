#!/usr/bin/python3
"""cutbench report: a static HTML site from a results directory.

Reads <results>/manifest.json (written by `cutbench report`), each case's HDF5 file and the
reference CSVs, draws every figure a case declares ([[plots]] in its TOML file) with the paper's
numbers overlaid, and lists every check record (paper | cutbench | error | tolerance | status).
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

UNITS = {  # symbol -> (factor to SI, offset)
    "1": (1, 0), "-": (1, 0), "%": (0.01, 0), "m": (1, 0), "mm": (1e-3, 0), "um": (1e-6, 0),
    "rad": (1, 0), "deg": (math.pi / 180, 0), "Pa": (1, 0), "kPa": (1e3, 0), "MPa": (1e6, 0),
    "GPa": (1e9, 0), "N": (1, 0), "kN": (1e3, 0), "N/m": (1, 0), "N/mm": (1e3, 0), "J/m^2": (1, 0),
    "s": (1, 0), "ms": (1e-3, 0), "us": (1e-6, 0), "m/s": (1, 0), "m/min": (1 / 60, 0),
    "mm/min": (1e-3 / 60, 0), "K": (1, 0), "kg/m^3": (1, 0), "g/cm^3": (1e3, 0), "1/m": (1, 0),
    "N m/m": (1, 0), "Pa m^0.5": (1, 0), "MPa m^0.5": (1e6, 0),
}
STATUS_CLASS = {"PASS": "pass", "FAIL": "fail", "NOT RUN": "notrun", "NOT IMPLEMENTED": "ni"}
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


def draw_F_glyphs(ax, sx, sy, snap, c, plot):
    """Deformation-gradient glyphs: each particle's domain, a square of the particle spacing in the
    reference configuration, drawn deformed by its F (the parallelograms of Nairn 2015 Fig. 2)."""
    from matplotlib.collections import PolyCollection
    F = np.stack([snap[k][()] for k in ("F_xx", "F_xy", "F_yx", "F_yy")], axis=1).reshape(-1, 2, 2)
    a = 0.5 * particle_spacing(sx, sy)
    corners = np.array([[-a, -a], [a, -a], [a, a], [-a, a]])
    verts = np.einsum("pij,cj->pci", F, corners) + np.stack([sx, sy], axis=1)[:, None, :]
    pc = PolyCollection(verts, cmap=plot.get("cmap", "Greys"), edgecolors="0.25", linewidths=0.15)
    if c is not None:
        pc.set_array(np.asarray(c, dtype=float))
    else:
        pc.set_facecolor("0.85")
    ax.add_collection(pc)
    ax.autoscale_view()
    return pc


def _attr(obj, name, default=""):
    v = obj.attrs.get(name, default)
    return v.decode() if isinstance(v, bytes) else v


def field_norm(values, plot):
    """Colour normalisation of a [[plots]] entry: `norm = "log"` (values below `vmin` drawn at
    `vmin`; default vmin = vmax / 10^decades, decades = 3) or linear; `vmin`/`vmax` fix the range
    (the colour bar then shows arrows at a clipped end). Returns (norm, values, extend)."""
    from matplotlib.colors import LogNorm, Normalize
    v = np.asarray(values, dtype=float)
    finite = v[np.isfinite(v)]
    lo = float(finite.min()) if finite.size else 0.0
    hi = float(finite.max()) if finite.size else 1.0
    vmax = float(plot["vmax"]) if "vmax" in plot else hi
    log = plot.get("norm") == "log"
    if log:
        vmax = vmax if vmax > 0 else 1.0
        vmin = float(plot["vmin"]) if "vmin" in plot else vmax * 10.0 ** -float(plot.get("decades", 3))
    else:
        vmin = float(plot["vmin"]) if "vmin" in plot else lo
    extend = {(True, True): "both", (True, False): "min", (False, True): "max",
              (False, False): "neither"}[(lo < vmin, hi > vmax)]
    if log:
        return LogNorm(vmin=vmin, vmax=vmax), np.clip(v, vmin, None), extend
    return Normalize(vmin=vmin, vmax=vmax), v, extend


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
    pc, label = None, None
    if field and field in snap and plot.get("center") != "cell":
        ds, on_cells = snap[field], False
    elif field and field in cf:
        ds, on_cells = cf[field], True
    else:
        ds = None
    if ds is not None:
        norm, values, extend = field_norm(ds[()], plot)
        cmap = plot.get("cmap", "viridis")
        if on_cells:
            pc = ax.tripcolor(tri, facecolors=values, norm=norm, cmap=cmap, shading="flat", edgecolors="none")
        else:
            pc = ax.tripcolor(tri, values, norm=norm, cmap=cmap, shading="gouraud")
        unit = _attr(ds, "units", "1")
        label = plot.get("clabel") or (field if unit in ("1", "") else "%s (%s)" % (field, unit))
        cb = fig.colorbar(pc, ax=ax, extend=extend, shrink=0.9)
        cb.set_label(label, fontsize=9)
        cb.ax.tick_params(labelsize=8)
    else:
        ax.triplot(tri, lw=0.2, color="0.5")
    if plot.get("mesh"):
        if "element" in cf:
            edges = element_edges(cells.tolist(), cf["element"][()])
        else:
            edges = {tuple(sorted(e)) for e in tri.edges.tolist()}
        segs = [((sx[a], sy[a]), (sx[b], sy[b])) for a, b in edges]
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


def draw_plot(case, plot, root, outdir):
    """Draw one [[plots]] entry; returns (png, svg) names or raises."""
    fig, ax = plt.subplots(figsize=tuple(plot.get("figsize", (6.4, 4.2))), dpi=110)
    h5 = h5py.File(case["h5"], "r") if case.get("h5") else None
    drawn = 0
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
            field = plot.get("field")
            c = snap[field][()] if field in snap else None
            # snapshot positions are stored in metres; draw them in the unit named in the axis label
            sx = convert(snap["x"][()], "m", axis_unit(plot.get("xlabel", ""), "mm"))
            sy = convert(snap["y"][()], "m", axis_unit(plot.get("ylabel", ""), "mm"))
            if "cells" in snap and plot.get("glyphs") != "F":
                draw_mesh_field(fig, ax, sx, sy, snap, plot)
                c = None  # colour bar drawn with the field
            elif plot.get("glyphs") == "F" and all(k in snap for k in ("F_xx", "F_xy", "F_yx", "F_yy")):
                sc = draw_F_glyphs(ax, sx, sy, snap, c, plot)
            else:
                sc = ax.scatter(sx, sy, c=c, s=plot.get("size", 2),
                                cmap=plot.get("cmap", "Greys"), marker="s", linewidths=0)
            if c is not None:
                fig.colorbar(sc, ax=ax, label=field)
            ax.set_aspect("equal")
            drawn += 1
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
    title = textwrap.fill(plot.get("title", ""), int(plot.get("title_wrap", 62)))
    if plot.get("kind") == "snapshot":
        fig.suptitle(title, fontsize=9)  # centred on the figure: an equal-aspect axes may be narrow
    else:
        ax.set_title(title, fontsize=9)
    ax.grid(True, alpha=0.3)
    if any(l.get("label") for l in plot.get("lines", [])):
        ax.legend(fontsize=7, loc=plot.get("legend", "best"))
    fig.tight_layout()
    base = "%s_%s_%s" % (case["paper"], case["item_id"], plot.get("name", "plot"))
    png, svg = base + ".png", base + ".svg"
    # an equal-aspect snapshot axes is shrunk inside its slot, which tight_layout does not see (the
    # y label was cut off): save snapshot plots with a tight bounding box
    tight = {"bbox_inches": "tight", "pad_inches": 0.1} if plot.get("kind") == "snapshot" else {}
    fig.savefig(os.path.join(outdir, "figures", png), metadata={"Software": None}, **tight)
    fig.savefig(os.path.join(outdir, "figures", svg), metadata={"Date": None, "Creator": None}, **tight)
    plt.close(fig)
    return png, svg


def fmt(v):
    if v is None:
        return "—"
    if isinstance(v, list):
        return "[" + ", ".join(fmt(x) for x in v) + "]"
    if isinstance(v, float):
        if v == 0:
            return "0"
        a = abs(v)
        return ("%.4g" % v) if 1e-3 <= a < 1e5 else ("%.3e" % v)
    return html.escape(str(v))


def badge(status):
    return '<span class="badge %s">%s</span>' % (STATUS_CLASS.get(status, "notrun"), html.escape(status))


CSS = """
body{font-family:system-ui,-apple-system,'Segoe UI',sans-serif;margin:0;color:#1d2330;background:#f6f7f9}
header{background:#1d2330;color:#fff;padding:14px 28px}header a{color:#cfe3ff}
main{padding:18px 28px;max-width:1200px}
h1{font-size:22px;margin:0}h2{font-size:18px;border-bottom:1px solid #d5d9e0;padding-bottom:4px}
h3{font-size:15px;margin:0 0 6px}
table{border-collapse:collapse;font-size:13px;margin:8px 0;background:#fff}
td,th{border:1px solid #d5d9e0;padding:4px 8px;text-align:left;vertical-align:top}
th{background:#eef1f5}
.badge{display:inline-block;padding:1px 7px;border-radius:9px;font-size:12px;font-weight:600;white-space:nowrap}
.pass{background:#d8f3dc;color:#1b5e20}.fail{background:#ffd6d6;color:#8b0000}
.notrun{background:#fff1c1;color:#7a5b00}.ni{background:#e4e6eb;color:#4a4f5c}
.case{background:#fff;border:1px solid #d5d9e0;border-radius:6px;padding:12px 16px;margin:14px 0}
.figs img{max-width:560px;width:100%;border:1px solid #e1e4ea;margin:4px 8px 4px 0}
.small{font-size:12px;color:#5b6272}.note{font-size:12px;color:#7a3e00}
"""


def checks_table(checks):
    """The table of check records (paper | cutbench | error | tolerance | status)."""
    rows = ["<table><tr><th>check</th><th>kind</th><th>paper / reference</th><th>cutbench</th>"
            "<th>error</th><th>tolerance</th><th>units</th><th>status</th><th>source</th></tr>"]
    for ch in checks:
        tol = ch.get("tolerance")
        tol_s = "range" if ch.get("tolerance_type") == "range" else (
            ("%s rel" % fmt(tol)) if ch.get("tolerance_type") == "relative" else fmt(tol))
        extra = ""
        if ch.get("known_failure"):
            extra += '<br><span class="note">known: %s</span>' % html.escape(ch["known_failure"])
        if ch.get("message"):
            extra += '<br><span class="small">%s</span>' % html.escape(ch["message"])
        rows.append("<tr><td>%s%s</td><td>%s</td><td>%s</td><td>%s</td><td>%s</td><td>%s</td>"
                    "<td>%s</td><td>%s</td><td class=\"small\">%s</td></tr>" % (
                        html.escape(ch["key"]),
                        ('<br><span class="small">%s</span>' % html.escape(ch["description"]))
                        if ch.get("description") else "",
                        ch["kind"], fmt(ch.get("reference")), fmt(ch.get("value")), fmt(ch.get("error")),
                        tol_s, html.escape(ch["units"]), badge(ch["status"]) + extra,
                        html.escape(ch.get("source", ""))))
    rows.append("</table>")
    return "".join(rows)


def full_summary(counts):
    """'3 PASS, 2 FAIL' for the recorded full-tier runs of a paper ('none' without any)."""
    if not counts:
        return "none"
    return ", ".join("%d %s" % (counts[k], k) for k in ("PASS", "FAIL", "NOT RUN", "NOT IMPLEMENTED") if counts.get(k))


def runs_summary(fr):
    """'3 of 30 (1 with a checkpoint)' for the stored full-tier solver runs ('-' without any)."""
    if not fr or not fr.get("total"):
        return "-"
    extra = " (%d with a checkpoint)" % fr["checkpoint"] if fr.get("checkpoint") else ""
    return "%d of %d%s" % (fr["stored"], fr["total"], extra)


def runs_total(by_paper):
    """The per-paper run counts summed (runs are never shared between papers)."""
    out = {"total": 0, "stored": 0, "checkpoint": 0}
    for fr in by_paper.values():
        for k in out:
            out[k] += fr.get(k, 0)
    return out


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
                with open(os.path.join(pdir, name), encoding="utf-8") as f:
                    rec = json.load(f)
                out[rec["case"]] = rec
    return out


def full_tier_block(rec):
    """A recorded full-tier run of a case: provenance line and its checks."""
    how = (rec.get("recorded") or {}).get("how", "")
    return ('<details><summary><b>Full tier (paper resolution), recorded run</b> %s '
            '<span class="small">run %s · software %s · %s thread(s) · %.3g s wall for this evaluation (≈ 0 where the solver runs came from a run cache; see below)</span></summary>'
            '<p class="small">How it was run: %s. Recorded in <code>reports/full_tier/%s.json</code>; '
            'the quick-tier table above is the one this report ran.</p>%s</details>') % (
        badge(rec.get("status", "NOT RUN")), html.escape(rec.get("date", "")), html.escape(rec.get("software", "")),
        html.escape(str(rec.get("threads", "?"))), rec.get("wall_time_s", 0) or 0, html.escape(how),
        html.escape(rec["case"]), checks_table(rec.get("checks") or []))


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


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--root", required=True)
    ap.add_argument("--results", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--full-tier", default=None,
                    help="recorded full-tier runs (default <root>/reports/full_tier)")
    a = ap.parse_args()
    full_records = load_full_records(a.full_tier or os.path.join(a.root, "reports", "full_tier"))
    with open(os.path.join(a.results, "manifest.json")) as f:
        man = json.load(f)
    os.makedirs(os.path.join(a.out, "figures"), exist_ok=True)
    papers = man["papers"]
    by_paper = {}
    for c in man["cases"]:
        by_paper.setdefault(c["paper"], []).append(c)

    summary_rows = []
    full_totals = {}
    totals = {"PASS": 0, "FAIL": 0, "NOT RUN": 0, "NOT IMPLEMENTED": 0}
    for pid in papers:
        cases = by_paper.get(pid, [])
        counts = {k: 0 for k in totals}
        full_counts = {}
        body = []
        meta = papers[pid].get("meta", {})
        body.append("<p>%s<br><span class=\"small\">DOI: %s</span></p>" % (
            html.escape(meta.get("citation", pid)), html.escape(meta.get("doi", "unknown"))))
        for c in cases:
            counts[c["status"]] = counts.get(c["status"], 0) + 1
            last = c.get("last_run") or {}
            pending = sum(1 for ch in (last.get("checks") or []) if ch.get("status") == "NOT IMPLEMENTED")
            extra_badge = (' <span class="badge ni">+%d checks await a solver</span>' % pending
                           if c["implemented"] and pending else "")
            parts = ['<div class="case" id="%s"><h3>%s — %s %s%s</h3>' % (
                html.escape(c["item_id"]), html.escape(c["item"]), html.escape(c["title"]), badge(c["status"]),
                extra_badge)]
            parts.append('<p class="small">case <code>%s</code> · solver %s · models %s · tiers %s%s</p>' % (
                html.escape(c["case"]), html.escape(c["solver"]), html.escape(", ".join(c["models"])),
                html.escape(", ".join(c["tiers"])),
                (" · last run %s (%s tier, %.2f s)" % (last.get("date"), last.get("tier"), last.get("wall_time_s", 0))
                 if last else "")))
            if c.get("requirement"):
                parts.append("<p>%s</p>" % html.escape(c["requirement"]))
            if not c["implemented"]:
                parts.append('<p class="note">Not implemented: %s</p>' % html.escape(c.get("reason", "")))
            for asm in c.get("assumptions", []):
                parts.append('<p class="note">Assumption: %s</p>' % html.escape(asm))
            for n in last.get("notes", []):
                parts.append('<p class="note">Note: %s</p>' % html.escape(n))
            figs = []
            if c.get("h5") or any(all("reference" in l for l in p.get("lines", [])) for p in c.get("plots", [])):
                for p in c.get("plots", []):
                    try:
                        r = draw_plot(c, p, a.root, a.out)
                    except Exception as e:  # a broken plot must not hide the rest of the report
                        parts.append('<p class="note">Plot %s failed: %s</p>' % (html.escape(p.get("name", "")),
                                                                                  html.escape(str(e))))
                        continue
                    if r:
                        figs.append('<a href="figures/%s"><img src="figures/%s" alt="%s"></a>' % (
                            r[1], r[0], html.escape(p.get("title", ""))))
            if figs:
                parts.append('<div class="figs">%s</div>' % "".join(figs))
            checks = last.get("checks") or []
            if checks:
                parts.append(checks_table(checks))
            elif c["implemented"]:
                parts.append('<p class="note">Not run yet in this results directory.</p>')
            fr = c.get("full_runs")
            if fr:
                parts.append('<p class="small">Full-tier campaign: %d of %d solver runs stored in '
                             '<code>reports/full_tier/runs</code>%s (<code>cutbench runs --case %s</code>).</p>' % (
                                 fr["stored"], fr["total"],
                                 ", %d with a checkpoint" % fr["checkpoint"] if fr.get("checkpoint") else "",
                                 html.escape(c["case"])))
            rec = full_records.get(c["case"])
            if rec:
                full_counts[rec.get("status", "NOT RUN")] = full_counts.get(rec.get("status", "NOT RUN"), 0) + 1
                parts.append(full_tier_block(rec))
            parts.append("</div>")
            body.append("".join(parts))
        for k in totals:
            totals[k] += counts.get(k, 0)
        write(os.path.join(a.out, pid + ".html"), page(pid, "".join(body)))
        summary_rows.append("<tr><td><a href=\"%s.html\">%s</a></td><td>%s</td><td>%d</td><td>%d</td><td>%d</td>"
                            "<td>%d</td><td>%d</td><td>%s</td><td>%s</td></tr>" % (
                                pid, pid, html.escape(papers[pid].get("meta", {}).get("citation", "")),
                                len(cases), counts["PASS"], counts["FAIL"], counts["NOT RUN"],
                                counts["NOT IMPLEMENTED"], full_summary(full_counts),
                                runs_summary(man.get("full_runs", {}).get(pid))))
        for k, v in full_counts.items():
            full_totals[k] = full_totals.get(k, 0) + v
    body = ("<p>Software %s · manifest written %s</p>" % (html.escape(man.get("software", "")),
                                                          html.escape(man.get("date", ""))) +
            "<table><tr><th>paper</th><th>citation</th><th>cases</th><th>%s</th><th>%s</th><th>%s</th><th>%s</th>"
            "<th>full tier, recorded runs</th><th>full tier, stored solver runs</th></tr>"
            % (badge("PASS"), badge("FAIL"), badge("NOT RUN"), badge("NOT IMPLEMENTED")) +
            "".join(summary_rows) +
            "<tr><th>all</th><th></th><th>%d</th><th>%d</th><th>%d</th><th>%d</th><th>%d</th><th>%s</th><th>%s</th>"
            "</tr></table>" % (
                sum(totals.values()), totals["PASS"], totals["FAIL"], totals["NOT RUN"], totals["NOT IMPLEMENTED"],
                full_summary(full_totals), runs_summary(runs_total(man.get("full_runs", {})))) +
            "<p class=\"small\">A case is PASS when every check it could evaluate passed (a documented known "
            "failure stays FAIL in its row); NOT RUN when its inputs are missing; NOT IMPLEMENTED when its "
            "model or solver does not exist yet. The statuses are those of the quick tier this report ran; the "
            "last column counts the recorded runs of the full tier (paper resolution, CPU-hours, not part of the "
            "main job; reports/full_tier, written by reports/record_full_tier.py), shown under each case; the "
            "last counts the distinct solver runs the full-tier cases need and how many of them the repository "
            "keeps (reports/full_tier/runs: the campaign that accumulates them across machines; "
            "<code>cutbench runs --paper P</code>).</p>")
    write(os.path.join(a.out, "index.html"), page("summary", body))
    print("report: %d cases, %s" % (sum(totals.values()), totals))


if __name__ == "__main__":
    main()
