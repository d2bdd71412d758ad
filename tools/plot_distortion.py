#!/usr/bin/env python3
"""Plot the distortion figures of a seqmassage run directory.

    plot_distortion.py RUN_DIR [--out DIR] [--frame NAME_OR_INDEX] [--log] [--formats png,svg]
                       [--dpi DPI]

Reads RUN_DIR/summary.csv (required), RUN_DIR/distortion/<frame name>.csv (optional, per
triangle; output.per_triangle_csv) and RUN_DIR/iterations.csv (optional, per iteration;
output.iterations) and writes PNG and SVG files to RUN_DIR/plots (or --out):

  shear_per_frame        max and mean shear per frame, before (green) and after (blue)
                         (like Figure 5 of the Mesh Massage paper)
  shear_histogram_<f>    per-triangle shear distribution of one frame, before vs after (Figure 7)
  convergence            distortion and distances against iteration (Figure 8), only when
                         iterations.csv exists: the --frame frame, else the frames whose shear
                         was measured after every iteration (output.iterations.shear_frames),
                         else every logged frame (shear then at the first and last iteration)

Shear is the symmetric maximum shear of eq. 8 (0 for a congruent triangle). Columns are read by
header name; extra columns are ignored, empty cells are treated as missing (NaN), `inf`/`nan` are
accepted. Exit status: 0 on success, 1 on bad input or missing matplotlib, 2 on bad usage.
"""

import argparse
import csv
import math
import os
import sys

GREEN = "#2ca02c"
BLUE = "#1f77b4"
SHEAR_LABEL = "symmetric maximum shear (eq. 8, dimensionless)"

SUMMARY_REQUIRED = ["frame", "file", "shear_max_before", "shear_mean_before",
                    "shear_max_after", "shear_mean_after"]
SUMMARY_NUMERIC = ["vertices", "triangles", "shear_max_before", "shear_mean_before",
                   "shear_p95_before", "shear_max_after", "shear_mean_after", "shear_p95_after",
                   "dist_out_to_in_max", "dist_out_to_in_rms", "dist_in_to_out_max",
                   "dist_in_to_out_rms", "iterations", "seconds"]
DISTORTION_REQUIRED = ["shear_before", "shear_after"]
ITERATION_REQUIRED = ["frame", "iteration"]
ITERATION_METRICS = ["shear_max", "shear_mean", "max_dist_m_to_n", "rms_dist_m_to_n",
                     "max_dist_n_to_m", "rms_dist_n_to_m", "energy"]


class InputError(Exception):
    """A problem with an input file; the message names the file."""


def load_matplotlib():
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        sys.stderr.write(
            "plot_distortion.py: error: matplotlib is not available for %s\n"
            "  install it with: apt-get install python3-matplotlib\n"
            "  (then run the script with /usr/bin/python3 if another python3 is first on PATH)\n"
            % sys.executable)
        sys.exit(1)
    from matplotlib.ticker import MaxNLocator
    globals()["MaxNLocator"] = MaxNLocator
    return plt


# ---------------------------------------------------------------------------------------------
# Reading

def parse_number(text, path, line, column):
    """float of a cell; empty or missing cell -> NaN; anything else non-numeric is an error."""
    if text is None:
        return math.nan
    text = text.strip()
    if text == "":
        return math.nan
    try:
        return float(text)
    except ValueError:
        raise InputError("%s: line %d: column '%s': not a number: '%s'"
                         % (path, line, column, text))


def read_table(path, required, numeric, optional_numeric=True):
    """Rows of a CSV as dicts; `numeric` columns (those present) parsed with parse_number."""
    try:
        handle = open(path, newline="", encoding="utf-8")
    except OSError as e:
        raise InputError("%s: cannot open: %s" % (path, e.strerror or e))
    with handle:
        reader = csv.reader(handle)
        try:
            header = next(reader, None)
        except csv.Error as e:
            raise InputError("%s: not a CSV file: %s" % (path, e))
        if header is None or not any(h.strip() for h in header):
            raise InputError("%s: empty file (no header line)" % path)
        header = [h.strip() for h in header]
        missing = [c for c in required if c not in header]
        if missing:
            raise InputError("%s: missing required column%s: %s (header: %s)"
                             % (path, "s" if len(missing) > 1 else "", ", ".join(missing),
                                ",".join(header)))
        index = {}
        for i, name in enumerate(header):
            index.setdefault(name, i)
        present_numeric = [c for c in numeric if c in index]
        rows = []
        try:
            for cells in reader:
                line = reader.line_num
                if not cells or all(not c.strip() for c in cells):
                    continue
                row = {}
                for name, i in index.items():
                    row[name] = cells[i].strip() if i < len(cells) else ""
                for name in present_numeric:
                    row[name] = parse_number(row[name], path, line, name)
                row["_line"] = line
                rows.append(row)
        except csv.Error as e:
            raise InputError("%s: line %d: malformed CSV: %s" % (path, reader.line_num, e))
    return header, rows


def read_summary(run_dir):
    path = os.path.join(run_dir, "summary.csv")
    if not os.path.isfile(path):
        raise InputError("%s: summary file not found" % path)
    _, rows = read_table(path, SUMMARY_REQUIRED, SUMMARY_NUMERIC + ["frame"])
    if not rows:
        raise InputError("%s: no frame rows after the header" % path)
    for row in rows:
        f = row["frame"]
        if not math.isfinite(f) or f != int(f):
            raise InputError("%s: line %d: column 'frame': not a frame index: '%s'"
                             % (path, row["_line"], f))
        row["frame"] = int(f)
        row["name"] = os.path.splitext(row["file"])[0] if row["file"] else "frame_%d" % row["frame"]
    return path, rows


def distortion_path(run_dir, row):
    """The per-triangle CSV of a summary row, or None."""
    base = os.path.join(run_dir, "distortion")
    for candidate in (row["name"] + ".csv", row["file"] + ".csv"):
        p = os.path.join(base, candidate)
        if row["file"] and os.path.isfile(p):
            return p
    return None


def read_distortion(path):
    _, rows = read_table(path, DISTORTION_REQUIRED, DISTORTION_REQUIRED)
    if not rows:
        raise InputError("%s: no triangle rows after the header" % path)
    return [r["shear_before"] for r in rows], [r["shear_after"] for r in rows]


def finite(values):
    return [v for v in values if math.isfinite(v)]


# ---------------------------------------------------------------------------------------------
# Figures

FORMATS = ("png", "svg")
DPI = 120


def save(fig, out_dir, stem, written):
    for ext in FORMATS:
        p = os.path.join(out_dir, "%s.%s" % (stem, ext))
        fig.savefig(p, dpi=DPI if ext == "png" else None)
        written.append(p)


def for_axis(values, log):
    """Non-finite values are gaps; on a log axis non-positive values are gaps too."""
    return [v if math.isfinite(v) and (not log or v > 0) else math.nan for v in values]


def plot_per_frame(plt, rows, log, out_dir, written):
    frames = [r["frame"] for r in rows]
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for ax, kind, title in ((axes[0], "max", "Maximum shear per frame"),
                            (axes[1], "mean", "Mean shear per frame")):
        before = for_axis([r["shear_%s_before" % kind] for r in rows], log)
        after = for_axis([r["shear_%s_after" % kind] for r in rows], log)
        marker = "o" if len(frames) <= 60 else None
        ax.plot(frames, before, color=GREEN, marker=marker, markersize=3, label="before")
        ax.plot(frames, after, color=BLUE, marker=marker, markersize=3, label="after")
        ax.set_title(title)
        ax.set_xlabel("frame index")
        ax.xaxis.set_major_locator(MaxNLocator(integer=True))
        ax.set_ylabel(SHEAR_LABEL)
        if log and any(math.isfinite(v) for v in before + after):
            ax.set_yscale("log")
        ax.grid(True, alpha=0.3)
        ax.legend()
    fig.tight_layout()
    save(fig, out_dir, "shear_per_frame", written)
    plt.close(fig)


def choose_frame(run_dir, rows, selector):
    """(row, csv path) of the histogram frame, or (None, None) when there is none."""
    if selector is not None:
        matches = [r for r in rows if selector in (str(r["frame"]), r["file"], r["name"])]
        if not matches:
            raise InputError("%s: no frame '%s' (give a frame index, file or name)"
                             % (os.path.join(run_dir, "summary.csv"), selector))
        row = matches[0]
        path = distortion_path(run_dir, row)
        if path is None:
            raise InputError("%s: no per-triangle CSV for frame '%s'"
                             % (os.path.join(run_dir, "distortion", row["name"] + ".csv"),
                                selector))
        return row, path
    best = None
    for row in rows:
        path = distortion_path(run_dir, row)
        if path is None:
            continue
        key = row["shear_max_before"]
        key = key if not math.isnan(key) else -math.inf
        if best is None or key > best[0]:
            best = (key, row, path)
    return (best[1], best[2]) if best else (None, None)


def plot_histogram(plt, row, path, log, out_dir, written):
    before, after = read_distortion(path)
    fb, fa = finite(before), finite(after)
    notes = []
    dropped = (len(before) - len(fb)) + (len(after) - len(fa))
    if dropped:
        notes.append("%d non-finite values left out" % dropped)
    if log:
        zb, za = sum(1 for v in fb if v <= 0), sum(1 for v in fa if v <= 0)
        fb, fa = [v for v in fb if v > 0], [v for v in fa if v > 0]
        if zb or za:
            notes.append("shear 0 (not on log axis): %d before, %d after" % (zb, za))
    values = fb + fa
    fig, ax = plt.subplots(figsize=(7, 4.5))
    if values:
        lo, hi = min(values), max(values)
        nbins = 50
        if log:
            if hi <= lo:
                lo, hi = lo / 1.5, hi * 1.5
            ratio = (hi / lo) ** (1.0 / nbins)
            bins = [lo * ratio ** i for i in range(nbins + 1)]
            ax.set_xscale("log")
        else:
            lo = min(lo, 0.0)
            if hi <= lo:
                hi = lo + 1.0
            bins = [lo + (hi - lo) * i / nbins for i in range(nbins + 1)]
        for vals, colour, what in ((fb, GREEN, "before"), (fa, BLUE, "after")):
            ax.hist(vals, bins=bins, color=colour, alpha=0.35)
            ax.hist(vals, bins=bins, color=colour, histtype="step", linewidth=1.5,
                    label="%s (%d triangles)" % (what, len(vals)))
        ax.legend()
    else:
        notes.append("no values to plot")
    ax.set_title("Per-triangle shear, frame %d (%s)" % (row["frame"], row["name"]))
    ax.set_xlabel(SHEAR_LABEL)
    ax.set_ylabel("number of triangles")
    ax.grid(True, alpha=0.3)
    if notes:
        ax.text(0.98, 0.70, "\n".join(notes), transform=ax.transAxes, ha="right", va="top",
                fontsize=8, color="0.3")
    fig.tight_layout()
    safe = "".join(c if c.isalnum() or c in "-_." else "_" for c in row["name"])
    save(fig, out_dir, "shear_histogram_%s" % safe, written)
    plt.close(fig)
    return notes


METRIC_LABELS = {
    "shear_max": "max shear", "shear_mean": "mean shear", "energy": "energy",
    "max_dist_m_to_n": "output vertices to input surface",
    "rms_dist_m_to_n": "output vertices to input surface",
    "max_dist_n_to_m": "input samples to output surface",
    "rms_dist_n_to_m": "input samples to output surface",
}


def shear_every_iteration(rows):
    """Whether some row between a frame's first and last iteration has a shear value."""
    last = {}
    for r in rows:
        last[r["frame"]] = max(last.get(r["frame"], -math.inf), r["iteration"])
    return any(0 < r["iteration"] < last[r["frame"]] and math.isfinite(r.get("shear_max", math.nan))
               for r in rows)


def plot_convergence(plt, path, selector, log, out_dir, written):
    header, rows = read_table(path, ITERATION_REQUIRED, ["iteration"] + ITERATION_METRICS)
    metrics = [m for m in ITERATION_METRICS if m in header]
    if not rows:
        raise InputError("%s: no iteration rows after the header" % path)
    if not metrics:
        raise InputError("%s: none of the metric columns %s" % (path, ", ".join(ITERATION_METRICS)))
    for row in rows:
        if math.isnan(row["iteration"]):
            raise InputError("%s: line %d: column 'iteration' is empty" % (path, row["_line"]))
    note = None
    if selector is not None:
        chosen = [r for r in rows if r["frame"] in selector]
        if chosen:
            rows = chosen
    elif "shear_max" in metrics and shear_every_iteration(rows):
        # Figure 8: the frames whose shear was measured after every iteration
        # (output.iterations.shear_frames), not every logged frame.
        frames_with_shear = {r["frame"] for r in rows
                             if 0 < r["iteration"] and math.isfinite(r["shear_max"])}
        full = {f for f in frames_with_shear
                if shear_every_iteration([r for r in rows if r["frame"] == f])}
        rows = [r for r in rows if r["frame"] in full]
    frames = []
    for r in rows:
        if r["frame"] not in frames:
            frames.append(r["frame"])
    if "shear_max" in metrics and not shear_every_iteration(rows):
        note = ("shear measured at the first and last iteration only\n"
                "(output.iterations.shear_frames measures it after every one)")

    groups = [("Maximum shear", SHEAR_LABEL, ["shear_max"]),
              ("Mean shear", SHEAR_LABEL, ["shear_mean"]),
              ("Maximum distance", "distance (model units)", ["max_dist_m_to_n", "max_dist_n_to_m"]),
              ("RMS distance", "distance (model units)", ["rms_dist_m_to_n", "rms_dist_n_to_m"]),
              ("Energy (eq. 7, after the solve)", "energy", ["energy"])]
    groups = [(t, y, [m for m in ms if m in metrics]) for t, y, ms in groups]
    groups = [g for g in groups if g[2]]
    ncols = 2 if len(groups) > 1 else 1
    nrows = (len(groups) + ncols - 1) // ncols
    fig, axes = plt.subplots(nrows, ncols, figsize=(5.5 * ncols, 3.8 * nrows), squeeze=False)
    cmap = plt.get_cmap("viridis")
    styles = ["-", "--"]
    show_legend = len(frames) <= 8
    for k, (title, ylabel, ms) in enumerate(groups):
        ax = axes[k // ncols][k % ncols]
        plotted = False
        for fi, frame in enumerate(frames):
            fr = sorted((r for r in rows if r["frame"] == frame), key=lambda r: r["iteration"])
            if len(frames) == 1:
                colour = BLUE
            elif len(frames) <= 10:
                colour = plt.get_cmap("tab10")(fi)
            else:
                colour = cmap(0.9 * fi / (len(frames) - 1))
            for mi, m in enumerate(ms):
                points = [(r["iteration"], v) for r, v in zip(fr, for_axis([r[m] for r in fr], log))
                          if math.isfinite(v)]
                plotted = plotted or bool(points)
                what = METRIC_LABELS.get(m, m)
                label = what if len(frames) == 1 else ("frame %s" % frame if len(ms) == 1
                                                       else "frame %s, %s" % (frame, what))
                # shear at the first and last iteration only: points, no line between them
                ends_only = m.startswith("shear") and not shear_every_iteration(fr)
                ax.plot([p[0] for p in points], [p[1] for p in points],
                        linestyle="none" if ends_only else styles[mi % 2], color=colour,
                        marker="o", markersize=2.5, label=label)
        ax.set_title(title if len(frames) != 1 else "%s, frame %s" % (title, frames[0]))
        ax.set_xlabel("iteration (0 = input frame)")
        ax.xaxis.set_major_locator(MaxNLocator(integer=True))
        ax.set_ylabel(ylabel)
        if log and plotted:
            ax.set_yscale("log")
        ax.grid(True, alpha=0.3)
        if show_legend or len(ms) > 1 and len(frames) == 1:
            ax.legend(fontsize=7)
        if note and ms[0].startswith("shear") and k == 0:
            ax.text(0.5, 0.5, note, transform=ax.transAxes, ha="center", va="center",
                    fontsize=7, color="0.35")
    for k in range(len(groups), nrows * ncols):
        axes[k // ncols][k % ncols].set_visible(False)
    if not show_legend:
        fig.suptitle("%d frames (colour: frame order)" % len(frames))
    fig.tight_layout()
    save(fig, out_dir, "convergence", written)
    plt.close(fig)
    return frames


# ---------------------------------------------------------------------------------------------

def main(argv=None):
    parser = argparse.ArgumentParser(
        description="Plot the distortion figures (PNG and SVG) of a seqmassage run directory.")
    parser.add_argument("run_dir", metavar="RUN_DIR", help="directory containing summary.csv")
    parser.add_argument("--out", metavar="DIR", help="output directory (default RUN_DIR/plots)")
    parser.add_argument("--frame", metavar="NAME_OR_INDEX",
                        help="frame for the histogram (and convergence): index, file or name; "
                             "default: largest max shear before among frames with a distortion CSV")
    parser.add_argument("--log", action="store_true",
                        help="log-scale y axes (histogram: log-spaced bins, log x)")
    parser.add_argument("--formats", default="png,svg", metavar="LIST",
                        help="comma-separated image formats among png and svg (default png,svg)")
    parser.add_argument("--dpi", type=int, default=120, help="PNG resolution (default 120)")
    args = parser.parse_args(argv)
    formats = tuple(f.strip().lower() for f in args.formats.split(",") if f.strip())
    if not formats or any(f not in ("png", "svg") for f in formats):
        parser.error("--formats: give png, svg or png,svg (got '%s')" % args.formats)
    if args.dpi < 10:
        parser.error("--dpi must be >= 10")
    global FORMATS, DPI
    FORMATS, DPI = formats, args.dpi

    plt = load_matplotlib()
    try:
        if not os.path.isdir(args.run_dir):
            raise InputError("%s: run directory not found" % args.run_dir)
        _, rows = read_summary(args.run_dir)
        out_dir = args.out or os.path.join(args.run_dir, "plots")
        try:
            os.makedirs(out_dir, exist_ok=True)
        except OSError as e:
            raise InputError("%s: cannot create output directory: %s" % (out_dir, e.strerror or e))
        written = []
        plot_per_frame(plt, rows, args.log, out_dir, written)

        row, path = choose_frame(args.run_dir, rows, args.frame)
        if row is None:
            print("no per-triangle CSVs in %s: histogram skipped"
                  % os.path.join(args.run_dir, "distortion"))
        else:
            plot_histogram(plt, row, path, args.log, out_dir, written)

        it_path = os.path.join(args.run_dir, "iterations.csv")
        if os.path.isfile(it_path):
            selector = None
            if args.frame is not None and row is not None:
                selector = {str(row["frame"]), row["name"], row["file"]}
            frames = plot_convergence(plt, it_path, selector, args.log, out_dir, written)
            print("convergence: frame%s %s" % ("" if len(frames) == 1 else "s",
                                                ", ".join(str(f) for f in frames)))
        else:
            print("%s not found: convergence figure skipped" % it_path)
    except InputError as e:
        sys.stderr.write("plot_distortion.py: error: %s\n" % e)
        return 1
    for p in written:
        print("wrote %s" % p)
    return 0


if __name__ == "__main__":
    sys.exit(main())
