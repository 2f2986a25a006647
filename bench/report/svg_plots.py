"""Hand-written SVG plots for the benchmark report (standard library only).

One function, loglog(): points and lines on log-log axes with decade ticks, a legend, and
optional fitted power laws drawn dashed. Values at or below `floor` are drawn at the floor
(an error of exactly 0 cannot sit on a log axis) and the axis label says so.
"""
import math
from xml.sax.saxutils import escape

PALETTE = ["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2",
           "#17becf", "#7f7f7f", "#bcbd22"]
MARKERS = ["circle", "square", "triangle", "diamond", "tri_down", "cross"]  # hollow needs a filled shape


def power_law_fit(points):
    """Least-squares fit of log y = log c + p log x; returns (p, c) or None (< 2 points)."""
    pts = [(math.log(x), math.log(y)) for x, y in points if x > 0 and y > 0]
    if len(pts) < 2:
        return None
    n = float(len(pts))
    mx = sum(p[0] for p in pts) / n
    my = sum(p[1] for p in pts) / n
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    if sxx == 0:
        return None
    p = sum((a - mx) * (b - my) for a, b in pts) / sxx
    return p, math.exp(my - p * mx)


def _marker(kind, x, y, r, color, filled=True):
    fill = color if filled else "white"
    if kind == "circle":
        return '<circle cx="%.1f" cy="%.1f" r="%.1f" fill="%s" stroke="%s" stroke-width="1.3"/>' % (
            x, y, r, fill, color)
    if kind == "square":
        return '<rect x="%.1f" y="%.1f" width="%.1f" height="%.1f" fill="%s" stroke="%s" ' \
               'stroke-width="1.3"/>' % (x - r, y - r, 2 * r, 2 * r, fill, color)
    if kind in ("triangle", "tri_down"):
        s = 1 if kind == "triangle" else -1
        pts = "%.1f,%.1f %.1f,%.1f %.1f,%.1f" % (x, y - s * 1.2 * r, x - 1.1 * r, y + s * 0.8 * r,
                                                 x + 1.1 * r, y + s * 0.8 * r)
        return '<polygon points="%s" fill="%s" stroke="%s" stroke-width="1.3"/>' % (pts, fill, color)
    if kind == "diamond":
        pts = "%.1f,%.1f %.1f,%.1f %.1f,%.1f %.1f,%.1f" % (x, y - 1.3 * r, x + r, y, x, y + 1.3 * r,
                                                           x - r, y)
        return '<polygon points="%s" fill="%s" stroke="%s" stroke-width="1.3"/>' % (pts, fill, color)
    return ('<path d="M%.1f %.1fL%.1f %.1fM%.1f %.1fL%.1f %.1f" stroke="%s" stroke-width="2"/>'
            % (x - r, y - r, x + r, y + r, x - r, y + r, x + r, y - r, color))


def _decades(lo, hi):
    """Whole decades around [lo, hi], with a little room so no point sits on the frame."""
    a, b = int(math.floor(math.log10(lo / 1.3))), int(math.ceil(math.log10(hi * 1.3)))
    if a == b:
        b = a + 1
    return a, b


def _fmt_pow(e):
    return "10<tspan dy=\"-6\" font-size=\"9\">%d</tspan>" % e


def loglog(path, title, xlabel, ylabel, series, floor=None, fits=False, note=None,
           width=760, height=480):
    """Write a log-log plot.

    series: [{"name", "points": [(x, y, label_or_None), ...], "line": bool, "hollow": [bool...]}]
    fits: draw each series' fitted power law (dashed) and put the exponent in the legend.
    """
    allx = [p[0] for s in series for p in s["points"] if p[0] and p[0] > 0]
    ally = [max(p[1], floor) if floor else p[1] for s in series for p in s["points"]
            if p[1] is not None and (p[1] > 0 or floor)]
    if not allx or not ally:
        allx, ally = [1.0, 10.0], [1.0, 10.0]
    x0, x1 = _decades(min(allx), max(allx))
    y0, y1 = _decades(min(ally), max(ally))
    L, R, T, B = 78, 250, 44, 58
    pw, ph = width - L - R, height - T - B

    def X(x):
        return L + (math.log10(x) - x0) / float(x1 - x0) * pw

    def Y(y):
        if floor:
            y = max(y, floor)
        return T + ph - (math.log10(y) - y0) / float(y1 - y0) * ph

    o = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" viewBox="0 0 %d %d" '
         'font-family="DejaVu Sans, Arial, sans-serif" font-size="11">' % (width, height, width, height),
         '<rect width="100%" height="100%" fill="white"/>',
         '<text x="%d" y="22" font-size="14" font-weight="bold">%s</text>' % (L, escape(title))]
    # grid and ticks
    for e in range(x0, x1 + 1):
        xx = X(10.0 ** e)
        o.append('<line x1="%.1f" y1="%d" x2="%.1f" y2="%d" stroke="#ddd"/>' % (xx, T, xx, T + ph))
        o.append('<text x="%.1f" y="%d" text-anchor="middle">%s</text>' % (xx, T + ph + 18, _fmt_pow(e)))
        for k in range(2, 10):
            if e < x1:
                xm = X(k * 10.0 ** e)
                o.append('<line x1="%.1f" y1="%d" x2="%.1f" y2="%d" stroke="#999"/>' % (
                    xm, T + ph, xm, T + ph - 4))
    for e in range(y0, y1 + 1):
        yy = Y(10.0 ** e)
        o.append('<line x1="%d" y1="%.1f" x2="%d" y2="%.1f" stroke="#ddd"/>' % (L, yy, L + pw, yy))
        o.append('<text x="%d" y="%.1f" text-anchor="end">%s</text>' % (L - 6, yy + 4, _fmt_pow(e)))
    o.append('<rect x="%d" y="%d" width="%d" height="%d" fill="none" stroke="#333"/>' % (L, T, pw, ph))
    o.append('<text x="%.1f" y="%d" text-anchor="middle">%s</text>' % (L + pw / 2.0, height - 14,
                                                                         escape(xlabel)))
    o.append('<text transform="translate(18,%.1f) rotate(-90)" text-anchor="middle">%s</text>' % (
        T + ph / 2.0, escape(ylabel)))
    if floor:
        o.append('<line x1="%d" y1="%.1f" x2="%d" y2="%.1f" stroke="#888" stroke-dasharray="2,3"/>' % (
            L, Y(floor), L + pw, Y(floor)))
    ly = T + 4
    fitted = []
    for i, s in enumerate(series):
        color = s.get("color") or PALETTE[i % len(PALETTE)]
        marker = s.get("marker") or MARKERS[i % len(MARKERS)]
        pts = [p for p in s["points"] if p[0] and p[0] > 0 and p[1] is not None
               and (p[1] > 0 or floor)]
        if s.get("line") and len(pts) > 1:
            d = " ".join("%s%.1f %.1f" % ("M" if j == 0 else "L", X(p[0]), Y(p[1]))
                         for j, p in enumerate(pts))  # in the order given (e.g. tolerance)
            o.append('<path d="%s" fill="none" stroke="%s" stroke-width="1.4"/>' % (d, color))
        for j, p in enumerate(pts):
            hollow = bool(s.get("hollow") and s["hollow"][s["points"].index(p)])
            o.append(_marker(marker, X(p[0]), Y(p[1]), 4.2, color, filled=not hollow))
            if len(p) > 2 and p[2]:
                o.append('<text x="%.1f" y="%.1f" font-size="9" fill="%s">%s</text>' % (
                    X(p[0]) + 6, Y(p[1]) - 5, color, escape(p[2])))
        name = s["name"]
        if fits:
            f = power_law_fit([(p[0], p[1]) for p in pts])
            if f:
                pexp, c = f
                xs = [min(p[0] for p in pts), max(p[0] for p in pts)]
                o.append('<path d="M%.1f %.1fL%.1f %.1f" stroke="%s" stroke-width="1" '
                         'stroke-dasharray="6,4" fill="none"/>' % (
                             X(xs[0]), Y(c * xs[0] ** pexp), X(xs[1]), Y(c * xs[1] ** pexp), color))
                name += " (slope %.2f)" % pexp
                fitted.append((s["name"], pexp))
        o.append(_marker(marker, L + pw + 18, ly + 4, 4.2, color))
        words = name.split(" ")
        lines, cur = [], ""
        for w in words:
            if len(cur) + len(w) > 30:
                lines.append(cur)
                cur = w
            else:
                cur = (cur + " " + w).strip()
        lines.append(cur)
        for k, ln in enumerate(lines):
            o.append('<text x="%d" y="%.1f">%s</text>' % (L + pw + 28, ly + 8 + 13 * k, escape(ln)))
        ly += 13 * len(lines) + 6
    if note:
        for k, ln in enumerate(note.split("\n")):
            o.append('<text x="%d" y="%.1f" font-size="9" fill="#555">%s</text>' % (
                L + pw + 10, ly + 14 + 12 * k, escape(ln)))
    o.append("</svg>")
    with open(path, "w") as fh:
        fh.write("\n".join(o) + "\n")
    return fitted
