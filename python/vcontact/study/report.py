"""report.html of a study (docs/STUDY.md, "Report"): the outputs against each parameter, the
probabilities of the yes/no outputs with Wilson intervals, the parameters' first-order
influence, and the slowest and the failed runs with the command that reproduces each alone.
Charts are inline SVG, as in the engine's own report; the page reads nothing else.
"""

import html
import math
import shlex

import numpy as np

BINS = 8           # quantile bins of a parameter for the probability curves and the influence
Z95 = 1.959963985  # the standard normal's 97.5 % quantile: two-sided 95 % intervals
SLOWEST = 10
MAX_DOTS = 2000    # runs drawn per scatter


def wilson(k, n, z=Z95):
    """Wilson score interval of a proportion k/n (Wilson 1927): centre (k + z²/2)/(n + z²),
    half-width z sqrt(k(n−k)/n + z²/4)/(n + z²). (nan, nan) when n = 0."""
    if n == 0:
        return math.nan, math.nan
    centre = (k + z * z / 2) / (n + z * z)
    half = z * math.sqrt(k * (n - k) / n + z * z / 4) / (n + z * z)
    return max(0.0, centre - half), min(1.0, centre + half)


def bins_of(x, bins=BINS):
    """Bin index of each value: quantile bins (equal counts), fewer where values repeat (a grid
    or list parameter gets one bin per level)."""
    levels = np.unique(x)
    if len(levels) <= bins:
        return np.searchsorted(levels, x), levels
    edges = np.unique(np.quantile(x, np.linspace(0, 1, bins + 1)))
    idx = np.clip(np.searchsorted(edges, x, side="right") - 1, 0, len(edges) - 2)
    centres = np.array([np.mean(x[idx == b]) if np.any(idx == b) else np.nan
                        for b in range(len(edges) - 1)])
    return idx, centres


def first_order_index(x, y, bins=BINS):
    """First-order Sobol index S = Var(E[Y|X]) / Var(Y), estimated by the correlation ratio over
    quantile bins of X (η² = between-bin over total sum of squares), less the value η² takes
    with no dependence at all, (B − 1)/(N − 1), rescaled: S = (η² − b)/(1 − b), clipped at 0.
    nan when Y is constant or has fewer than 2 B finite values."""
    ok = np.isfinite(y)
    x, y = x[ok], y[ok]
    if len(y) < 2 * bins or np.ptp(y) == 0:
        return math.nan
    idx, _ = bins_of(x, bins)
    groups = np.unique(idx)
    mean = y.mean()
    total = np.sum((y - mean) ** 2)
    between = sum(np.sum(idx == g) * (y[idx == g].mean() - mean) ** 2 for g in groups)
    eta2 = between / total
    bias = (len(groups) - 1) / (len(y) - 1)
    return max(0.0, (eta2 - bias) / (1 - bias))


def _is_flag(y):
    finite = y[np.isfinite(y)]
    return len(finite) > 0 and np.all((finite == 0) | (finite == 1))


# --- SVG -------------------------------------------------------------------------------------

W, H, PAD = 300, 190, 38


def _scale(lo, hi, a, b):
    if not (math.isfinite(lo) and math.isfinite(hi)) or hi == lo:
        lo, hi = (lo - 1, hi + 1) if math.isfinite(lo) else (0, 1)
    return lambda v: a + (v - lo) / (hi - lo) * (b - a)


def _axes(xlabel, ylabel, xr, yr):
    fmt = lambda v: f"{v:.3g}"
    return (f'<line x1="{PAD}" y1="{H - PAD}" x2="{W - 8}" y2="{H - PAD}" stroke="#444"/>'
            f'<line x1="{PAD}" y1="8" x2="{PAD}" y2="{H - PAD}" stroke="#444"/>'
            f'<text x="{PAD}" y="{H - PAD + 13}" font-size="10">{fmt(xr[0])}</text>'
            f'<text x="{W - 8}" y="{H - PAD + 13}" font-size="10" text-anchor="end">'
            f'{fmt(xr[1])}</text>'
            f'<text x="{(W + PAD) / 2}" y="{H - 6}" font-size="11" text-anchor="middle">'
            f'{html.escape(xlabel)}</text>'
            f'<text x="{PAD - 3}" y="{H - PAD}" font-size="10" text-anchor="end">'
            f'{fmt(yr[0])}</text>'
            f'<text x="{PAD - 3}" y="14" font-size="10" text-anchor="end">{fmt(yr[1])}</text>'
            f'<text x="10" y="{(H - PAD) / 2}" font-size="11" text-anchor="middle" '
            f'transform="rotate(-90 10 {(H - PAD) / 2})">{html.escape(ylabel)}</text>')


def scatter_svg(x, y, bad, xlabel, ylabel):
    """y against x; runs that did not complete in red. Beyond MAX_DOTS runs, every k-th run
    (k = ceil(n / MAX_DOTS)), so that a page of a million runs stays a few megabytes."""
    stride = max(1, math.ceil(len(x) / MAX_DOTS))
    x, y, bad = x[::stride], y[::stride], bad[::stride]
    ok = np.isfinite(x) & np.isfinite(y)
    if not np.any(ok):
        return f"<p>{html.escape(ylabel)}: no finite value</p>"
    xr, yr = (x[ok].min(), x[ok].max()), (y[ok].min(), y[ok].max())
    sx, sy = _scale(*xr, PAD + 3, W - 12), _scale(*yr, H - PAD - 3, 12)
    dots = "".join(f'<circle cx="{sx(a):.1f}" cy="{sy(b):.1f}" r="2" '
                   f'fill="{"#c33" if f else "#36c"}" fill-opacity="0.6"/>'
                   for a, b, f in zip(x[ok], y[ok], bad[ok]))
    return f'<svg width="{W}" height="{H}">{_axes(xlabel, ylabel, xr, yr)}{dots}</svg>'


def probability_svg(x, flag, xlabel, ylabel):
    """P(flag) in bins of x, with the Wilson 95 % interval of each bin."""
    ok = np.isfinite(flag)
    idx, centres = bins_of(x[ok])
    flag = flag[ok]
    xr = (np.nanmin(centres), np.nanmax(centres))
    sx, sy = _scale(*xr, PAD + 8, W - 16), _scale(0, 1, H - PAD - 3, 12)
    parts, rows = [], []
    for b, c in enumerate(centres):
        n = int(np.sum(idx == b))
        if n == 0:
            continue
        k = int(np.sum(flag[idx == b]))
        lo, hi = wilson(k, n)
        rows.append((c, k, n, lo, hi))
        parts.append(f'<line x1="{sx(c):.1f}" x2="{sx(c):.1f}" y1="{sy(lo):.1f}" '
                     f'y2="{sy(hi):.1f}" stroke="#c33"/>'
                     f'<circle cx="{sx(c):.1f}" cy="{sy(k / n):.1f}" r="3" fill="#c33"/>')
    svg = (f'<svg width="{W}" height="{H}">{_axes(xlabel, "P(" + ylabel + ")", xr, (0, 1))}'
           + "".join(parts) + "</svg>")
    return svg, rows


# --- page ------------------------------------------------------------------------------------

def _reproduce(study, out, run):
    return (f"vcontact study {shlex.quote(study.path)} --run {run} "
            f"--out {shlex.quote(out + f'/run_{run}')}")


def _runs_table(study, table, runs, out):
    head = "".join(f"<th>{html.escape(n)}</th>" for n in study.names)
    lines = []
    for i in runs:
        values = "".join(f"<td>{table[n][i]:.6g}</td>" for n in study.names)
        lines.append(f"<tr><td>{i}</td>{values}<td>{html.escape(str(table['status'][i]))}</td>"
                     f"<td>{table['wall_time_s'][i]:.3f}</td>"
                     f"<td>{html.escape(str(table['message'][i]))}</td>"
                     f"<td><code>{html.escape(_reproduce(study, out, i))}</code></td></tr>")
    return (f"<table><tr><th>run</th>{head}<th>status</th><th>wall s</th><th>message</th>"
            f"<th>reproduce alone</th></tr>{''.join(lines)}</table>")


def _influence_table(study, table, outputs):
    rows = []
    for o in outputs:
        y = np.asarray(table[o], float)
        s = {n: first_order_index(np.asarray(table[n], float), y) for n in study.names}
        ranked = sorted(s.items(), key=lambda kv: -1 if math.isnan(kv[1]) else -kv[1])
        cells = "".join(f"<td>{html.escape(n)} {v:.2f}</td>" if not math.isnan(v)
                        else f"<td>{html.escape(n)} –</td>" for n, v in ranked)
        rows.append(f"<tr><th>{html.escape(o)}</th>{cells}</tr>")
    return "<table>" + "".join(rows) + "</table>"


def write_report(study, table, path, out):
    status = table["status"]
    bad = status != "completed"
    n = len(status)
    outputs = [o["name"] for o in study.outputs]
    flags = [o for o in outputs if _is_flag(np.asarray(table[o], float))]
    numeric = [o for o in outputs if o not in flags]
    parts = [f"<h1>Study {html.escape(study.path)}</h1>",
             f"<p>{html.escape(study.description)}</p>",
             f"<p>{n} runs of {html.escape(study.scenario_path)}; design {study.design}, seed "
             f"{study.seed}; {int(np.sum(status == 'completed'))} completed, "
             f"{int(np.sum(status == 'stopped'))} stopped, {int(np.sum(status == 'error'))} "
             f"errors; {np.sum(table['wall_time_s']):.1f} s of run time in all.</p>"]
    if flags:
        parts.append("<h2>Probabilities (95 % Wilson intervals)</h2><table>"
                     "<tr><th>output</th><th>yes</th><th>runs</th><th>P</th>"
                     "<th>95 % interval</th></tr>")
        for o in flags:
            y = np.asarray(table[o], float)
            ok = np.isfinite(y)
            k, m = int(np.sum(y[ok])), int(np.sum(ok))
            lo, hi = wilson(k, m)
            parts.append(f"<tr><td>{html.escape(o)}</td><td>{k}</td><td>{m}</td>"
                         f"<td>{k / m if m else math.nan:.3f}</td>"
                         f"<td>[{lo:.3f}, {hi:.3f}]</td></tr>")
        parts.append("</table>")
        for o in flags:
            parts.append(f"<h3>P({html.escape(o)}) against each parameter</h3><div>")
            for p in study.names:
                svg, _ = probability_svg(np.asarray(table[p], float),
                                         np.asarray(table[o], float), p, o)
                parts.append(svg)
            parts.append("</div>")
    parts.append("<h2>Most influential parameters</h2><p>First-order Sobol index of each "
                 "output by the correlation ratio over 8 quantile bins of the parameter, "
                 "bias-corrected (docs/STUDY.md, \"Report\"); largest first.</p>")
    parts.append(_influence_table(study, table, outputs))
    shown = "" if n <= MAX_DOTS else f" Every {math.ceil(n / MAX_DOTS)}th run is drawn."
    parts.append("<h2>Outputs against each parameter</h2><p>Blue: completed runs; red: "
                 f"stopped or failed.{shown}</p>")
    for o in numeric:
        parts.append(f"<h3>{html.escape(o)}</h3><div>")
        for p in study.names:
            parts.append(scatter_svg(np.asarray(table[p], float), np.asarray(table[o], float),
                                     bad, p, o))
        parts.append("</div>")
    slow = np.argsort(-table["wall_time_s"], kind="stable")[:SLOWEST]
    parts.append("<h2>Slowest runs</h2>" + _runs_table(study, table, slow, out))
    failed = np.flatnonzero(bad)
    parts.append(f"<h2>Stopped and failed runs ({len(failed)})</h2>"
                 + (_runs_table(study, table, failed[:200], out) if len(failed) else
                    "<p>none</p>"))
    page = ("<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>vcontact study</title>"
            "<style>body{font-family:sans-serif;margin:1.5em}table{border-collapse:collapse}"
            "td,th{border:1px solid #ccc;padding:2px 6px;font-size:12px}svg{margin:4px}"
            "</style></head><body>" + "".join(parts) + "</body></html>\n")
    tmp = path + ".tmp"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(page)
    import os
    os.replace(tmp, path)
