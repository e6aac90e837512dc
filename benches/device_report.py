#!/usr/bin/env python3
"""The figures of a device session (`benches/device-session.sh`), read from each run's files.

    python3 benches/device_report.py row LABEL RC WALL STEM FLAGS   # one pull-off's table row
    python3 benches/device_report.py trace STEM ELAPSED              # one line of a run's trace
    python3 benches/device_report.py parity GPU_STEM CPU_STEM        # the parity lines
    python3 benches/device_report.py accuracy STEM RATIO RC WALL     # one --accuracy line
    python3 benches/device_report.py headline OUT                    # the headline and targets

A finished run's figures come from its summary JSON (`runs[0]`: the grid's own |min F̄|, its
states, CG iterations and solver wall time); a run cut at its limit has no JSON, and its
figures come from its partial states file `<stem>.incomplete-<pid>.csv`, marked as partial
(the states held back during the search for the minimum are written later, so its CG
iterations are a lower bound). Standard library only: the device machine has no extra packages.
"""
import csv
import glob
import json
import math
import os
import re
import sys

NAN = float("nan")


def load_json(path):
    """The JSON at `path`, or None."""
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def partial_rows(stem):
    """The rows of a run's newest partial states file (cut runs), and its path."""
    paths = sorted(glob.glob(glob.escape(stem) + ".incomplete-*.csv"), key=os.path.getmtime)
    if not paths:
        return [], None
    try:
        with open(paths[-1], newline="") as f:
            return list(csv.DictReader(f)), paths[-1]
    except (OSError, csv.Error):
        return [], paths[-1]


def fmt(v, spec):
    """`v` formatted, or an em dash where it is missing or not finite."""
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "—"
    return format(v, spec)


def run_figures(stem, rc):
    """A pull-off's figures: from its summary JSON, else from its partial states."""
    j = load_json(stem + ".json")
    if j and j.get("runs"):
        r = j["runs"][0]
        cost = r.get("cost") or {}
        return {
            "source": "summary JSON",
            "complete": bool(j.get("complete")),
            "states": r.get("states"),
            "cg": r.get("cg_iterations"),
            "cg_lower_bound": False,
            "solver_wall": r.get("wall_s"),
            "grid_f": r.get("f_ad_bar"),
            "lowest_f": r.get("lowest_f_bar"),
            "estimate": j.get("f_ad_bar"),
            "uncertainty": j.get("f_ad_bar_uncertainty"),
            "c_at_min": r.get("c_bar_at_min"),
            "d_at_min": r.get("d_bar_at_min"),
            "solves": cost.get("solves"),
            "onsets": cost.get("onsets"),
            "readbacks": cost.get("readbacks"),
            "warnings": j.get("warnings") or [],
        }
    rows, path = partial_rows(stem)
    f = [float(x["f_bar"]) for x in rows if x.get("f_bar")]
    last = rows[-1] if rows else {}
    return {
        "source": f"partial states {os.path.basename(path)}" if path else "no states file",
        "complete": False,
        "states": len(rows),
        "cg": sum(int(x.get("cg_iterations") or 0) for x in rows),
        "cg_lower_bound": True,
        "solver_wall": None,
        "grid_f": None,
        "lowest_f": min(f) if f else None,
        "estimate": None,
        "uncertainty": None,
        "c_at_min": float(last["c_bar"]) if last.get("c_bar") else None,
        "d_at_min": float(last["d_bar"]) if last.get("d_bar") else None,
        "solves": None,
        "onsets": None,
        "readbacks": None,
        "warnings": [],
    }


def status_of(rc):
    """A run's exit status in words."""
    if rc == "0":
        return "complete"
    if rc in ("124", "130", "137"):
        return "cut at its limit"
    return f"exit {rc}"


ROW_HEADER = (
    "| run | flags | status | wall (s) | solver (s) | states | solves | CG iterations | "
    "wall / CG it. (ms) | grid \\|min F̄\\| | Δx → 0 estimate | figures from |\n"
    "| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |"
)


def row(label, rc, wall, stem, flags):
    """One pull-off's table row; also writes `<stem>.row.json` for the headline."""
    wall = float(wall)
    g = run_figures(stem, rc)
    g.update(label=label, rc=rc, status=status_of(rc), wall=wall, flags=flags)
    with open(stem + ".row.json", "w") as f:
        json.dump(g, f)
    cg = g["cg"] or 0
    cg_text = ("≥ " if g["cg_lower_bound"] and cg else "") + str(cg)
    if g["grid_f"] is not None:
        f_text = f"{g['grid_f']:.7f}"
    elif g["lowest_f"] is not None:
        f_text = f"(lowest so far {abs(g['lowest_f']):.6f})"
    else:
        f_text = "—"
    est = (
        f"{g['estimate']:.5f} ± {g['uncertainty']:.5f}"
        if g["estimate"] is not None and g["uncertainty"] is not None
        else "—"
    )
    per_it = wall / cg * 1e3 if cg else NAN
    print(
        f"| {label} | `{flags}` | {g['status']} | {wall:.1f} | {fmt(g['solver_wall'], '.1f')} | "
        f"{g['states']} | {fmt(g['solves'], 'd')} | {cg_text} | {fmt(per_it, '.3f')} | {f_text} | "
        f"{est} | {g['source']} |"
    )
    for w in g["warnings"][:3]:
        print(f"|  | warning: {w.replace('|', '/')} | | | | | | | | | | |")


def trace(stem, elapsed):
    """One line of a growing run's trace: elapsed s, states, CG iterations, last d̄ c̄ F̄."""
    rows, _ = partial_rows(stem)
    if rows:
        it = sum(int(x.get("cg_iterations") or 0) for x in rows)
        r = rows[-1]
        print(f"{elapsed},{len(rows)},{it},{r['d_bar']},{r['c_bar']},{r['f_bar']}")


def parity(gpu_stem, cpu_stem):
    """The grid's own |min F̄| and CG iterations of the GPU (f32) and CPU (f64) runs."""
    g, c = load_json(gpu_stem + ".json"), load_json(cpu_stem + ".json")
    if not (g and g.get("runs") and c and c.get("runs")):
        missing = [s for s, j in ((gpu_stem, g), (cpu_stem, c)) if not (j and j.get("runs"))]
        print(f"(no parity figures: no summary from {', '.join(map(os.path.basename, missing))})")
        return
    fg, fc = g["runs"][0].get("f_ad_bar"), c["runs"][0].get("f_ad_bar")
    ig, ic = g["runs"][0]["cg_iterations"], c["runs"][0]["cg_iterations"]
    if fg is None or fc is None:
        print("(no parity figures: a run did not reach the force minimum)")
        return
    d = abs(fg - fc) / fc
    print(
        f"- grid's own |min F̄| (`runs[0].f_ad_bar`): GPU (f32) {fg:.7f}, CPU (f64) {fc:.7f}: "
        f"relative difference {d:.2e} (target ≤ 1e-5: {'met' if d <= 1e-5 else 'missed'})"
    )
    r = ig / ic
    print(
        f"- CG iterations: GPU (f32) {ig}, CPU (f64) {ic}: ×{r:.3f} "
        f"(target within 10 %: {'met' if abs(r - 1) <= 0.10 else 'missed'})"
    )


def reference(ratio):
    """The reference table's row for `ratio`, or None."""
    path = os.path.join(os.path.dirname(__file__), "..", "data", "reference", "adhesive-force.csv")
    try:
        with open(path, newline="") as f:
            for r in csv.DictReader(f):
                if abs(float(r["ratio"]) - float(ratio)) < 1e-9:
                    return float(r["f_ad_bar"]), float(r["f_ad_bar_uncertainty"])
    except OSError:
        pass
    return None


def accuracy(stem, ratio, rc, wall):
    """One `--accuracy` run's line: its estimate, the reference's interval, its wall time."""
    j = load_json(stem + ".json")
    wall = float(wall)
    head = f"- R1/R2 = {ratio}: {status_of(rc)}, {wall:.1f} s (target ≤ 5 s: {'met' if wall <= 5 else 'missed'})"
    if not j or j.get("f_ad_bar") is None:
        print(f"{head}; no estimate (no summary JSON or no run reached the minimum)")
        return
    f, u = j["f_ad_bar"], j.get("f_ad_bar_uncertainty") or NAN
    grids = ", ".join(r["grid"] for r in j.get("runs", []))
    text = f"{head}; |min F̄| = {f:.5f} ± {u:.5f} ({j.get('estimate')}, grids {grids}, {j.get('cg_iterations')} CG iterations, target met: {j.get('target_met')})"
    ref = reference(ratio)
    if ref:
        fr, ur = ref
        inside = abs(f - fr) <= ur
        overlap = abs(f - fr) <= ur + u
        text += (
            f"; reference {fr:.5f} ± {ur:.5f}: difference {100 * (f / fr - 1):+.2f} %, "
            f"{'inside' if inside else 'outside'} its interval"
            f"{'' if inside else (', intervals overlap' if overlap else ', intervals disjoint')}"
        )
    print(text)


def bench_iteration_ms(out, name, nx, ny):
    """The GPU's CG iteration time (ms) at nx × ny from a bench CSV in `out`, or None."""
    try:
        with open(os.path.join(out, name), newline="") as f:
            for r in csv.DictReader(f):
                if r["backend"] == "gpu" and int(r["nx"]) == nx and int(r["ny"]) == ny:
                    return float(r["cg_iteration_ms"])
    except (OSError, KeyError, ValueError):
        pass
    return None


def floor_ms(out):
    """The 2048² CG iteration's counted floor (ms): its floor bytes from the bench profile's
    text over the copy bandwidth of the floors step, or None."""
    try:
        text = open(os.path.join(out, "bench.txt")).read()
        m = re.findall(r"profile --backends gpu (\d+)×(\d+).*?the floor of ([\d.]+) MB", text, re.S)
        mb = {(int(a), int(b)): float(c) for a, b, c in m}.get((2048, 2048))
        with open(os.path.join(out, "floors.csv"), newline="") as f:
            bw = float(next(csv.DictReader(f))["copy_bandwidth_gbs"])
        if mb:
            return mb / bw, mb, bw
    except (OSError, ValueError, StopIteration, KeyError):
        pass
    return None


def headline(out):
    """The session's headline (its largest run) and every target the files let us check."""
    lines = []
    rows = {}
    for p in glob.glob(os.path.join(out, "*.row.json")):
        r = load_json(p)
        if r:
            rows[r["label"]] = r
    measure = next((r for k, r in sorted(rows.items()) if k.endswith("-measure") and k.startswith("gpu-") and not k.startswith("gpu-parity")), None)
    curve = next((r for k, r in sorted(rows.items()) if k.endswith("-curve")), None)
    top = measure or curve
    if top:
        cg = top["cg"] or 0
        f = top["grid_f"]
        lines.append(
            f"**{top['label']}** (`{top['flags']}`): {top['status']} in {top['wall']:.1f} s, "
            f"{top['states']} states, {'≥ ' if top['cg_lower_bound'] else ''}{cg} CG iterations, "
            + (f"grid |min F̄| {f:.7f}" if f is not None else "no force minimum reached")
            + f" (figures from {top['source']})."
        )
    targets = []
    if measure:
        targets.append(("adhesive force < 60 s", measure["complete"] and measure["wall"] < 60, f"{measure['status']}, {measure['wall']:.1f} s"))
        m = re.search(r"--grid (\d+)", measure["flags"])
        nx = int(m.group(1)) if m else 0
        it = bench_iteration_ms(out, "bench-measure.csv", nx, nx // 2)
        if it and measure["cg"]:
            counted = measure["cg"] * it / 1e3
            targets.append((
                "wall ≤ 1.5 × CG iterations × iteration time",
                measure["complete"] and measure["wall"] <= 1.5 * counted,
                f"{measure['wall']:.1f} s against {measure['cg']} × {it:.4f} ms = {counted:.1f} s (×{measure['wall'] / counted:.2f})",
            ))
    if curve:
        targets.append(("whole curve < 3 min", curve["complete"] and curve["wall"] < 180, f"{curve['status']}, {curve['wall']:.1f} s"))
    it2048 = bench_iteration_ms(out, "bench.csv", 2048, 2048)
    fl = floor_ms(out)
    if it2048 and fl:
        ms, mb, bw = fl
        targets.append((
            "2048² CG iteration ≤ 2.5 × its counted floor",
            it2048 <= 2.5 * ms,
            f"{it2048:.4f} ms against {mb:.1f} MB / {bw:.0f} GB/s = {ms:.4f} ms (×{it2048 / ms:.2f})",
        ))
    elif it2048:
        targets.append(("2048² CG iteration ≤ 2.5 × its counted floor", None, f"{it2048:.4f} ms; no floor measured"))
    if targets:
        lines.append("")
        lines.append("| target | met | measured |")
        lines.append("| --- | --- | --- |")
        for name, met, text in targets:
            lines.append(f"| {name} | {'—' if met is None else ('yes' if met else '**no**')} | {text} |")
    print("\n".join(lines) if lines else "(no pull-off ran in this session)")


def main(argv):
    cmd, args = argv[1], argv[2:]
    {"row": row, "trace": trace, "parity": parity, "accuracy": accuracy, "headline": headline}[cmd](*args)


if __name__ == "__main__":
    main(sys.argv)
