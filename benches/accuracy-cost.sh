#!/usr/bin/env bash
# The cost of an `--accuracy` answer, ratio by ratio (a benchmark, not a test: times are this
# machine's): `jkrbem simulate --ratio R --accuracy TARGET` for every ratio of the reference
# table, one run at a time, each under a time limit, and one CSV row per ratio beside the
# reference value it should lie within.
#
#   benches/accuracy-cost.sh [OUT_DIR] [TARGET] [BACKEND] [TIME_LIMIT] [RATIOS]
#   defaults:                jkrbem-out/accuracy-cost 1% cpu 4min "1 1.5 2 3 5 7 10 15 20 25 35 50"
#
# Writes OUT_DIR/accuracy-cost.csv (ratio, target, target_met, f_ad_bar, uncertainty, the
# grids the answer is from, n_d, wall_s: the whole command's wall time, cg_iterations: over
# every grid run, the time limit's fallback grid included, reference, reference_uncertainty,
# within_reference) and each run's states and summary.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-jkrbem-out/accuracy-cost}
target=${2:-1%}
backend=${3:-cpu}
limit=${4:-4min}
ratios=${5:-"1 1.5 2 3 5 7 10 15 20 25 35 50"}
bin=${JKRBEM_BIN:-target/release/jkrbem}
[ -x "$bin" ] || cargo build --release
mkdir -p "$out"
# SUMMARY_ONLY=1: only rebuild the CSV from the runs already in OUT_DIR.
for r in $ratios; do
  [ -n "${SUMMARY_ONLY:-}" ] && break
  echo "== R1/R2 = $r: --accuracy $target --backend $backend --time-limit $limit" >&2
  rm -f "$out/r$r.csv" "$out/r$r"-n*.csv
  start=$(date +%s.%N)
  "$bin" simulate --ratio "$r" --accuracy "$target" --backend "$backend" --time-limit "$limit" \
    --out "$out/r$r.csv" --summary "$out/r$r.json" >"$out/r$r.txt" 2>&1 || true
  python3 -c "print($(date +%s.%N) - $start)" >"$out/r$r.wall"
  grep -E "adhesive force|target" "$out/r$r.txt" >&2 || true
done
python3 - "$out" "$target" "$ratios" <<'EOF'
import csv, glob, json, sys
out, target, ratios = sys.argv[1], sys.argv[2], sys.argv[3].split()
table = {float(r["ratio"]): r for r in csv.DictReader(open("data/reference/adhesive-force.csv"))}
rows = []
for r in ratios:
    try:
        s = json.load(open(f"{out}/r{r}.json"))
    except (OSError, ValueError):
        rows.append({"ratio": r, "target": target})
        continue
    runs = s.get("runs", [])
    ref = table.get(float(r), {})
    f, u = s.get("f_ad_bar"), s.get("f_ad_bar_uncertainty")
    rf, ru = ref.get("f_ad_bar"), ref.get("f_ad_bar_uncertainty")
    within = None
    if f is not None and rf:
        within = abs(f - float(rf)) <= u + float(ru)
    rows.append({
        "ratio": r, "target": target, "target_met": s.get("target_met"),
        "f_ad_bar": f, "uncertainty": u,
        "grids": ";".join(str(x.get("grid")) for x in runs),
        "n_d": max((x.get("n_d") or 0 for x in runs), default=None),
        "wall_s": round(float(open(f"{out}/r{r}.wall").read()), 1),
        "cg_iterations": sum(int(row["cg_iterations"])
                             for f in glob.glob(f"{out}/r{r}-n*.csv") + glob.glob(f"{out}/r{r}.csv")
                             for row in csv.DictReader(open(f))),
        "reference": rf, "reference_uncertainty": ru, "within_reference": within,
    })
fields = ["ratio", "target", "target_met", "f_ad_bar", "uncertainty", "grids", "n_d", "wall_s",
          "cg_iterations", "reference", "reference_uncertainty", "within_reference"]
with open(f"{out}/accuracy-cost.csv", "w", newline="") as fh:
    w = csv.DictWriter(fh, fieldnames=fields)
    w.writeheader()
    w.writerows(rows)
print(open(f"{out}/accuracy-cost.csv").read())
EOF
