"""The oracle's speed against a plain Embree loop over the same rays, measured and written in one
place (scripts/oracle-ratios): runs bench_hard_shadow and bench_area_shadow RUNS times, takes each
light's `oracle / occluded16` ratio (each run's is already the median of its interleaved
repetitions), and

  - compares each light's median over the runs with the median it last wrote
    (docs/oracle-ratios.json): one more than 10% below it is a regression, reported, and the
    script exits 1 without writing anything (--accept writes anyway: a slowdown taken on purpose,
    to be said in the commit);
  - otherwise writes docs/oracle-ratios.json, the table between docs/benchmarks.md's
    "BEGIN oracle-ratios" markers and the sentence between the README's "BEGIN oracle-ratio"
    markers.

Nothing in those places is typed by hand, so the published ratios cannot go stale unnoticed: a
change to the oracle runs this before it lands."""
import argparse
import datetime
import json
import os
import pathlib
import re
import subprocess
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from doc_markers import write_between_markers  # noqa: E402

REGRESSION = 0.10  # a median more than this far below the last written one fails


def run_bench(command):
    """{light: (ratio, ratio without the near fields, near field's share)} from one bench run."""
    out = subprocess.run(command, check=True, capture_output=True, text=True).stdout
    lights, current = {}, None
    for line in out.splitlines():
        m = re.match(r"light (\w+)", line)
        if m:
            current = m.group(1)
            continue
        m = re.search(r"rtcOccluded16 .*oracle / occluded16 = ([0-9.]+)", line)
        if m and current:
            lights[current] = [float(m.group(1)), None, None]
        m = re.search(r"without the near fields: +oracle / occluded16 = ([0-9.]+) \(their share "
                      r"of the oracle's time: (-?[0-9.]+)%\)", line)
        if m and current in lights:
            lights[current][1] = float(m.group(1))
            lights[current][2] = float(m.group(2)) / 100.0
    if not lights:
        sys.exit(f"error: no ratios in the output of {' '.join(command)}:\n{out}")
    return lights, out


def median(values):
    v = sorted(values)
    n = len(v)
    return v[n // 2] if n % 2 else 0.5 * (v[n // 2 - 1] + v[n // 2])


def measure(build, runs):
    benches = {
        "hard": [f"{build}/bench/bench_hard_shadow", "--reps", "9"],
        "area": [f"{build}/bench/bench_area_shadow", "--reps", "5", "--no-adaptive"],
    }
    result, header = {}, None
    for run in range(runs):
        for bench, command in benches.items():
            lights, out = run_bench(command)
            header = header or out.splitlines()[0]
            print(f"run {run + 1}/{runs}, {bench}: " +
                  ", ".join(f"{k} {v[0]:.2f}" for k, v in lights.items()), flush=True)
            for light, (ratio, far, share) in lights.items():
                entry = result.setdefault(f"{bench}.{light}", {"ratios": [], "without_near": [],
                                                                 "near_share": []})
                entry["ratios"].append(ratio)
                if far is not None:
                    entry["without_near"].append(far)
                    entry["near_share"].append(share)
    for entry in result.values():
        entry["median"] = median(entry["ratios"])
    return result, header


def machine(header):
    """'N cores, Embree V' from the bench's first line."""
    m = re.search(r"Embree ([0-9.]+)", header)
    return f"{os.cpu_count()} cores, Embree {m.group(1) if m else 'unknown'}"


def table(figures):
    rows = ["| pass, light | oracle / rtcOccluded16 (median, range) | without the near fields | "
            "the near field's share of the oracle's time |", "|---|---|---|---|"]
    for key, e in figures["lights"].items():
        far = f"{median(e['without_near']):.2f}" if e["without_near"] else "n/a"
        share = f"{100 * median(e['near_share']):.1f}%" if e["near_share"] else "n/a"
        rows.append(f"| {key.replace('.', ', ')} | {e['median']:.2f} ({min(e['ratios']):.2f}-"
                    f"{max(e['ratios']):.2f}) | {far} | {share} |")
    rows.append("")
    rows.append(f"{figures['runs']} runs of each bench (`bench_hard_shadow --reps 9`, "
                f"`bench_area_shadow --reps 5`), {figures['date']}, {figures['machine']}; each "
                "run's ratio is the median of its interleaved repetitions. Written by "
                "`scripts/oracle-ratios`, which fails when a median falls more than "
                f"{int(100 * REGRESSION)}% below the one it last wrote.")
    return "\n".join(rows)


def sentence(figures):
    hard = [e["median"] for k, e in figures["lights"].items() if k.startswith("hard.")]
    area = [e["median"] for k, e in figures["lights"].items() if k.startswith("area.")]
    def span(values):  # "0.84" where the lights agree, else "0.84 to 0.88"
        lo, hi = f"{min(values):.2f}", f"{max(values):.2f}"
        return lo if lo == hi else f"{lo} to {hi}"

    return (f"Its hard pass runs at {span(hard)} of a plain Embree "
            f"`rtcOccluded16` loop over the same rays and its sampled area pass at {span(area)} "
            f"(medians of {figures['runs']} runs, {figures['date']}: "
            "[docs/benchmarks.md](docs/benchmarks.md#the-oracle-against-plain-embree), written by "
            "`scripts/oracle-ratios`).")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build", default="build")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--root", default=".")
    ap.add_argument("--accept", action="store_true",
                    help="write the figures even where a median fell (a slowdown taken on purpose)")
    args = ap.parse_args()
    if args.runs < 1:
        sys.exit("error: --runs: at least 1")
    root = pathlib.Path(args.root)
    store = root / "docs" / "oracle-ratios.json"
    measured, header = measure(args.build, args.runs)
    last = json.loads(store.read_text())["lights"] if store.exists() else {}
    fell = []
    for key, e in measured.items():
        before = last.get(key, {}).get("median")
        verdict = ""
        if before is not None:
            change = e["median"] / before - 1.0
            verdict = f" (last written {before:.2f}, {100 * change:+.1f}%)"
            if change < -REGRESSION:
                fell.append(key)
                verdict += f"  <-- more than {int(100 * REGRESSION)}% below"
        print(f"{key:14s} median {e['median']:.2f}{verdict}")
    if fell and not args.accept:
        print(f"error: {', '.join(fell)} fell more than {int(100 * REGRESSION)}% below the last "
              f"written figure ({store}); nothing written (--accept to write anyway)",
              file=sys.stderr)
        return 1
    figures = {
        "date": datetime.date.today().isoformat(),
        "machine": machine(header),
        "runs": args.runs,
        "lights": measured,
    }
    store.write_text(json.dumps(figures, indent=2) + "\n")
    write_between_markers(root / "docs" / "benchmarks.md", "oracle-ratios", table(figures))
    write_between_markers(root / "README.md", "oracle-ratio", sentence(figures))
    print(f"wrote {store}, docs/benchmarks.md and README.md")
    return 0


if __name__ == "__main__":
    sys.exit(main())
