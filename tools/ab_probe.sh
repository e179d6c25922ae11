#!/bin/bash
# Before/after of two builds of a timing probe (e.g. two copies of the workload_probe binary
# from target/release/deps), alternating A, B, A, B, … N times so that drift on a shared
# machine reaches both alike; prints per shader × variant the median rate of each and the
# median of the per-pair ratios B/A with their range.
#
#   tools/ab_probe.sh A_BINARY B_BINARY [N=5] [VARIANTS=f32x16x2,f32x8x4]
#   (environment: SHADERS, ROUNDS as the probe reads them)
set -euo pipefail
A=$1; B=$2; N=${3:-5}; V=${4:-f32x16x2,f32x8x4}
LOG=$(mktemp)
for i in $(seq "$N"); do
  for bin in "$A" "$B"; do
    VARIANTS=$V "$bin" --bench 2>&1 | grep Mpts | awk -v t="$bin" -v i="$i" '{print i, t, $1, $2, $3}' >> "$LOG"
  done
done
python3 - "$A" "$B" "$LOG" <<'PY'
import collections, statistics as st, sys
a, b, log = sys.argv[1:4]
d = collections.defaultdict(dict)
for line in open(log):
    i, t, shader, variant, rate = line.split()
    d[(shader, variant)].setdefault(i, {})[t] = float(rate)
for (shader, variant), runs in d.items():
    pairs = [r for r in runs.values() if a in r and b in r]
    ratios = [r[b] / r[a] for r in pairs]
    print(f"{shader:8} {variant:9} A {st.median(r[a] for r in pairs):7.1f} B {st.median(r[b] for r in pairs):7.1f}"
          f"  B/A {st.median(ratios):.3f} [{min(ratios):.3f}..{max(ratios):.3f}]")
PY
rm -f "$LOG"
