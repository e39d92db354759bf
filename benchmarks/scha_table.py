#!/usr/bin/env python3
"""Adaptive harmonics (ah) against spherical cap harmonics (scha, Neumann and mixed) on the test
meshes: mean and max reconstruction error per order (relative to the bounding-box diagonal), the
boundary loop's max error at the top order and the fit time (after the parameterization), from
`capmesh harmonics --report`. Writes benchmarks/results/scha_table.md and prints it.

Timing: `cargo run --release --example scha_timing` (built first) parameterizes each mesh once
and runs `harmonics::analyze_map` (the CLI's `fit_seconds`: fit of every order, errors,
reconstruction, aspect ratio) `--reps` times with ah and scha Neumann alternating, on one thread,
in process CPU time, every scha run paying for building its basis afresh; the table gives the
medians and their ratio. CPU time on one thread because the machine these figures come from is
shared: there, medians of 3 wall-time runs of fresh CLI processes differed by a factor 0.7 to 1.7
between two bases doing the same work. The errors come from one `capmesh harmonics --report` per basis (they do not vary).

Usage: python3 benchmarks/scha_table.py [--order N] [--reps R] [--meshes NAME ...]
(defaults 15, 3, the open face and hand and the closed meshes but the 48k brain);
needs target/release/capmesh and target/release/examples/scha_timing.
"""
import argparse
import json
import pathlib
import subprocess
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
EXE = ROOT / "target/release/capmesh"
TIMING = ROOT / "target/release/examples/scha_timing"
MESHES = ["open_face_choi", "open_hand_choi", "closed_brain12k_choi", "closed_hippocampus_choi", "closed_bunny_npm",
          "closed_bird_skull_CPallidusA_choi", "closed_lung_rml_chaste"]
BASES = [("ah", []), ("scha neumann", ["--basis", "scha", "--boundary", "neumann"]),
         ("scha mixed", ["--basis", "scha", "--boundary", "mixed"])]


def timing(mesh, order, reps):
    """Median CPU seconds of analyze_map with ah and with scha Neumann (one thread)."""
    done = subprocess.run([str(TIMING), str(ROOT / "tests/data" / f"{mesh}.obj.gz"), str(order), str(reps)],
                          capture_output=True, text=True, check=True)
    line = next(l for l in done.stdout.splitlines() if l.startswith("TIMING "))
    ah, scha, ah_before, scha_before = map(float, line.split()[1:5])
    return {"ah": (ah, ah_before), "scha neumann": (scha, scha_before)}


def run(mesh, flags, order, tmp):
    report = pathlib.Path(tmp) / "r.json"
    cmd = [str(EXE), "harmonics", "--quiet", "--order", str(order), str(ROOT / "tests/data" / f"{mesh}.obj.gz"),
           "-o", str(pathlib.Path(tmp) / "out.ply"), "--report", str(report)] + flags
    done = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        return "rank deficient" if "rank deficient" in done.stderr else done.stderr.strip()[-80:]
    return json.loads(report.read_text())


def row(mesh, name, r, shown, seconds, ratio):
    if isinstance(r, str):
        return f"| {mesh} | {name} | " + " | ".join("-" for _ in shown) + f" | failed: {r} | - | - | - |"
    errors = {e["order"]: e for e in r["errors_by_order"]}
    cells = [f"{errors[o]['mean_relative']:.4f} / {errors[o]['max_relative']:.4f}" for o in shown]
    b = r.get("boundary_max_relative")
    boundary = "closed" if b is None else f"{b:.4f}"
    cap = r.get("basis_z_star", r["z_star"])
    where = f"Z* {r['z_star']:.3f}" + (", basis on the whole sphere" if cap != r["z_star"] else "")
    return f"| {mesh} ({where}) | {name} | " + " | ".join(cells) + f" | {boundary} | {seconds} | {ratio} |"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--order", type=int, default=15)
    parser.add_argument("--reps", type=int, default=3)
    parser.add_argument("--meshes", nargs="*", default=MESHES)
    args = parser.parse_args()
    order = args.order
    shown = [o for o in (5, 10, order) if o <= order]
    lines = [f"| mesh | basis | " + " | ".join(f"N={o} mean / max" for o in shown)
             + f" | boundary max | fit CPU s, 1 thread (median of {args.reps}) | fit time / ah's"
             + " | before issue 33's speed-up: CPU s, / ah's |",
             "|---|---|" + "---|" * len(shown) + "---|---|---|---|"]
    with tempfile.TemporaryDirectory() as tmp:
        for mesh in args.meshes:
            seconds = timing(mesh, order, args.reps)
            for name, flags in BASES:
                r = run(mesh, flags, order, tmp)
                if name in seconds:
                    (now, before), (ah_now, ah_before) = seconds[name], seconds["ah"]
                    t = f"{now:.3f}"
                    ratio = f"{now / ah_now:.2f} | {before:.3f}, {before / ah_before:.2f}"
                else:
                    t, ratio = "-", "- | -"
                lines.append(row(mesh, name, r, shown, t, ratio))
                print(lines[-1], flush=True)
    out = ROOT / "benchmarks/results/scha_table.md"
    out.write_text("\n".join(lines) + "\n")
    print(f"written to {out}")


if __name__ == "__main__":
    main()
