#!/usr/bin/env python3
"""Times the pre-warp of two rtm builds (or two targets of one) side by side, interleaved, and prints their ratio.

    python3 scripts/compare_builds.py [--rounds N] [--sizes LIST] [--reliefs LIST] [--methods LIST]
                                      [--threads LIST] [--min-time S] [--bar R] A_RTM A_ISA B_RTM B_ISA

Runs `rtm bench --sizes S --isa ISA --no-exact --no-reference --no-table1 --no-scene --json FILE` of build A and of
build B one after the other, one size at a time (the two runs of a size a few seconds apart, so that the host's drift,
which moves a figure by up to 1.5x within minutes on a shared guest, hits both alike), the order A, B in odd rounds
and B, A in even ones, for every size, N rounds. Each run gives a median pre-warp time a row (relief, size,
reconstruction, threads) of the lookup-table kernels of target ISA as `rtm bench --isa` names its rows (`generic`: the
reference kernels, one thread only; `auto`: the target `rtm bench` chooses). The report gives, a row, the median over
the rounds of each build's medians, `B speed / A` = A's time over B's (higher: B faster), and the lowest and highest
of the rounds' own ratios: a Markdown table on standard output, then a summary line (the range of the ratios, and in
how many rows they reach R, default 0.95: issue #18's bar for the Highway kernels against the hand-written ones);
progress on standard error.

Both builds must have `rtm bench` with these options and its JSON rows (any commit since the Highway kernels,
2026-12-02). Exits 1 with one line (after the progress of the runs before it) when an argument is wrong, a run fails,
or the two builds' runs do not give the same rows.

    python3 scripts/compare_builds.py --rounds 5 old/build/bin/rtm avx512 build/bin/rtm avx512
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile


def fail(message):
    sys.exit(f"compare_builds: {message}")


def csv_of(kind, allowed=None, integer=False):
    """An argparse type: a comma-separated list of KIND, each in `allowed` or a positive integer."""

    def parse(text):
        items = [x.strip() for x in text.split(",")]
        for x in items:
            if integer and not (x.isdigit() and int(x) > 0):
                raise argparse.ArgumentTypeError(f"{kind} '{x}' is not a positive integer (in '{text}')")
            if allowed is not None and x not in allowed:
                raise argparse.ArgumentTypeError(f"{kind} '{x}' is none of {', '.join(allowed)} (in '{text}')")
        return [int(x) for x in items] if integer else items

    return parse


def positive(kind, cast):
    def parse(text):
        try:
            value = cast(text)
        except ValueError:
            value = None
        if value is None or not value > 0:
            raise argparse.ArgumentTypeError(f"{kind} '{text}' is not a positive number")
        return value

    return parse


class Parser(argparse.ArgumentParser):
    def error(self, message):  # one line, exit 1 (argparse's own: usage and exit 2)
        fail(message)


def bench(rtm, isa, size, args, json_path):
    """{(relief, size, method, threads): median ms} of one `rtm bench` run of one size."""
    # The generic kernels' rows are the bench's reference rows (one thread); any other target's, its fast rows.
    command = [rtm, "bench", "--sizes", str(size), "--isa", isa, "--reliefs", ",".join(args.reliefs), "--methods",
               ",".join(args.methods), "--threads", ",".join(map(str, args.threads)), "--min-time",
               str(args.min_time), "--no-exact", "--no-table1", "--no-scene"]
    command += ([] if isa == "generic" else ["--no-reference"]) + ["--json", json_path]
    shown = " ".join(command)
    if os.path.exists(json_path):
        os.remove(json_path)  # (the previous run's)
    run = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if run.returncode != 0:
        last = run.stderr.strip().splitlines()[-1:] or ["no message"]
        fail(f"'{shown}' exited {run.returncode}: {last[0]}")
    try:
        with open(json_path) as f:
            rows = json.load(f)["rows"]
    except (OSError, ValueError, KeyError, TypeError) as e:
        fail(f"'{shown}' wrote no report of rows to {json_path} ({type(e).__name__}: {e})")
    out = {}
    for r in rows:
        if r.get("path") != "lut" or (r.get("isa") != isa if isa != "auto" else r.get("kernel") != "fast"):
            continue
        out[(r["relief"], r["size"], r["method"], r["threads"])] = r["prewarp_ms"]["median"]
    if not out:
        fail(f"'{shown}' gave no row of target {isa} (a target this CPU or build lacks?)")
    return out


def main():
    p = Parser(description="Two rtm builds' pre-warp times, interleaved (see the file's first comment).")
    p.add_argument("--rounds", type=positive("--rounds", int), default=3)
    p.add_argument("--sizes", type=csv_of("size", integer=True), default=[128, 256, 512, 1024, 2048, 4096])
    p.add_argument("--reliefs", type=csv_of("relief"), default=["bumps", "bricks", "ridges"])
    p.add_argument("--methods", type=csv_of("method", ["two-pass", "pipelined"]), default=["two-pass", "pipelined"])
    p.add_argument("--threads", type=csv_of("thread count", integer=True), default=[1, 2])
    p.add_argument("--min-time", type=positive("--min-time", float), default=0.25)
    p.add_argument("--bar", type=positive("--bar", float), default=0.95)
    p.add_argument("a_rtm")
    p.add_argument("a_isa")
    p.add_argument("b_rtm")
    p.add_argument("b_isa")
    args = p.parse_args()
    for rtm in (args.a_rtm, args.b_rtm):
        if not (os.path.isfile(rtm) and os.access(rtm, os.X_OK)):
            fail(f"'{rtm}' is not an executable file")

    times = {"A": {}, "B": {}}  # build -> row -> [median of each round]
    builds = {"A": (args.a_rtm, args.a_isa), "B": (args.b_rtm, args.b_isa)}
    with tempfile.TemporaryDirectory() as tmp:
        for rnd in range(args.rounds):
            for size in args.sizes:
                got = {}
                for name in ("A", "B") if rnd % 2 == 0 else ("B", "A"):
                    print(f"compare_builds: round {rnd + 1} of {args.rounds}, {size}^2, {name}", file=sys.stderr)
                    got[name] = bench(*builds[name], size, args, os.path.join(tmp, "bench.json"))
                if got["A"].keys() != got["B"].keys():
                    fail(f"the builds' runs at {size}^2 gave different rows: A {sorted(got['A'])}, "
                         f"B {sorted(got['B'])}")
                for name in ("A", "B"):
                    for row, ms in got[name].items():
                        times[name].setdefault(row, []).append(ms)

    order = {m: i for i, m in enumerate(args.methods)}
    rows = sorted(times["A"], key=lambda r: (args.sizes.index(r[1]), args.reliefs.index(r[0]), order[r[2]], r[3]))
    print(f"A: {args.a_rtm} --isa {args.a_isa}; B: {args.b_rtm} --isa {args.b_isa}; {args.rounds} rounds\n")
    print("| relief | size | method | threads | A ms | B ms | B speed / A | lowest, highest of the rounds |")
    print("|---|---:|---|---:|---:|---:|---:|---|")
    ratios = []
    for row in rows:
        a, b = times["A"][row], times["B"][row]
        ratio = statistics.median(a) / statistics.median(b)
        each = [x / y for x, y in zip(a, b)]
        ratios.append(ratio)
        relief, size, method, threads = row
        print(f"| {relief} | {size}^2 | {method} | {threads} | {statistics.median(a):.3f} | {statistics.median(b):.3f} "
              f"| {ratio:.2f} | {min(each):.2f}, {max(each):.2f} |")
    print(f"\n{len(ratios)} rows: B speed / A from {min(ratios):.2f} to {max(ratios):.2f}, median "
          f"{statistics.median(ratios):.2f}; >= {args.bar:g} in {sum(r >= args.bar for r in ratios)}")


if __name__ == "__main__":
    main()
