#!/usr/bin/env python3
"""anysl against the peer systems on the shared shading workload, in one run.

Runs `anysl bench workload` and `shared/bench/peers/run_peers.sh` (Dr.Jit by default)
alternately ROUNDS times, so that drift on a shared machine reaches both alike, and prints
one table per thread count: each system's median Mpts/s over the rounds and max abs error,
then the ratios the shading-speed issue asks for (anysl-f32x8 / drjit-llvm-avx2-frozen,
anysl-f32x16 / drjit-llvm-frozen, anysl-jit-x8 / anysl-f32x8, anysl-jit-x16 /
anysl-f32x16, 2 threads / 1 thread), each the median over the rounds of the ratio within a
round. The raw TSVs of every round are written to --out.

    python3 tools/compare_peers.py [--rounds 3] [--peers drjit drjit-avx2] [--out DIR]
"""
import argparse, os, statistics, subprocess, sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SHADERS = ["plastic", "checker", "wood", "granite"]


def tsv(text):
    rows = {}
    for line in text.splitlines():
        p = line.split("\t")
        if len(p) < 6 or p[0] == "system" or line.startswith("#"):
            continue
        rows[(p[0], p[1], int(p[2]))] = (float(p[3]), p[5].strip())
    return rows


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--peers", nargs="*", default=["drjit", "drjit-avx2"])
    ap.add_argument("--anysl", default=os.path.join(ROOT, "target", "release", "anysl"))
    ap.add_argument("--peer-script", default=os.path.join(ROOT, "..", "shared", "bench", "peers", "run_peers.sh"))
    ap.add_argument("--out", default=os.path.join(ROOT, "target", "peers"))
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    rounds = []
    for r in range(a.rounds):
        ours = subprocess.run([a.anysl, "bench", "workload"], capture_output=True, text=True, check=True).stdout
        peers = subprocess.run(["bash", a.peer_script, *a.peers], capture_output=True, text=True, check=True).stdout
        for name, text in (("anysl", ours), ("peers", peers)):
            with open(os.path.join(a.out, f"round{r + 1}-{name}.tsv"), "w") as f:
                f.write(text)
        rows = tsv(ours)
        rows.update(tsv(peers))
        rounds.append(rows)
        print(f"# round {r + 1} of {a.rounds} done", file=sys.stderr)

    def med(key):
        v = [rd[key][0] for rd in rounds if key in rd]
        return statistics.median(v) if v else float("nan")

    def ratio(num, den, t, s):
        v = [rd[(num, s, t)][0] / rd[(den, s, t)][0] for rd in rounds if (num, s, t) in rd and (den, s, t) in rd]
        return statistics.median(v) if v else float("nan")

    systems = sorted({k[0] for rd in rounds for k in rd})
    for t in (1, 2):
        print(f"\n### {t} thread{'s' if t > 1 else ''}: Mpts/s (median of {a.rounds} rounds), max abs err\n")
        print("| system | " + " | ".join(SHADERS) + " | max abs err |")
        print("|---|" + "---|" * (len(SHADERS) + 1))
        for sy in systems:
            if not any((sy, s, t) in rounds[0] for s in SHADERS):
                continue
            errs = ", ".join(rounds[0].get((sy, s, t), (0, "-"))[1] for s in SHADERS)
            print(f"| {sy} | " + " | ".join(f"{med((sy, s, t)):.2f}" for s in SHADERS) + f" | {errs} |")
        print()
        print("| ratio (median of per-round ratios) | " + " | ".join(SHADERS) + " | mean |")
        print("|---|" + "---|" * (len(SHADERS) + 1))
        for num, den in [("anysl-f32x8", "drjit-llvm-avx2-frozen"), ("anysl-f32x16", "drjit-llvm-frozen"),
                         ("anysl-jit-x8", "anysl-f32x8"), ("anysl-jit-x16", "anysl-f32x16")]:
            rs = [ratio(num, den, t, s) for s in SHADERS]
            print(f"| {num} / {den} | " + " | ".join(f"{x:.2f}" for x in rs) + f" | **{statistics.fmean(rs):.2f}** |")
    print("\n| 2 threads / 1 thread | " + " | ".join(SHADERS) + " |")
    print("|---|" + "---|" * len(SHADERS))
    for sy in ["anysl-f32x8", "anysl-f32x16", "anysl-jit-x16", "drjit-llvm-frozen"]:
        rs = []
        for s in SHADERS:
            v = [rd[(sy, s, 2)][0] / rd[(sy, s, 1)][0] for rd in rounds if (sy, s, 2) in rd and (sy, s, 1) in rd]
            rs.append(statistics.median(v) if v else float("nan"))
        print(f"| {sy} | " + " | ".join(f"{x:.2f}" for x in rs) + " |")


if __name__ == "__main__":
    main()
