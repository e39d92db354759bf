#!/usr/bin/env python3
"""Adaptive harmonics (ah) against spherical cap harmonics (scha, Neumann and mixed) on the test
meshes: mean and max reconstruction error per order (relative to the bounding-box diagonal), the
boundary loop's max error at the top order and the fit time (after the parameterization), from
`capmesh harmonics --report`. Writes benchmarks/results/scha_table.md and prints it.

Usage: python3 benchmarks/scha_table.py [ORDER] (default 15); needs target/release/capmesh.
"""
import json
import pathlib
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
EXE = ROOT / "target/release/capmesh"
MESHES = ["open_face_choi", "open_hand_choi", "closed_brain12k_choi", "closed_hippocampus_choi", "closed_bunny_npm"]
BASES = [("ah", []), ("scha neumann", ["--basis", "scha", "--boundary", "neumann"]), ("scha mixed", ["--basis", "scha", "--boundary", "mixed"])]


def run(mesh, flags, order, tmp):
    report = pathlib.Path(tmp) / "r.json"
    cmd = [str(EXE), "harmonics", "--quiet", "--order", str(order), str(ROOT / "tests/data" / f"{mesh}.obj.gz"),
           "-o", str(pathlib.Path(tmp) / "out.ply"), "--report", str(report)] + flags
    done = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        return "rank deficient" if "rank deficient" in done.stderr else done.stderr.strip()[-80:]
    return json.loads(report.read_text())


def main():
    order = int(sys.argv[1]) if len(sys.argv) > 1 else 15
    shown = [o for o in (5, 10, order) if o <= order]
    lines = [f"| mesh | basis | " + " | ".join(f"N={o} mean / max" for o in shown) + " | boundary max | fit s |",
             "|---|---|" + "---|" * len(shown) + "---|---|"]
    with tempfile.TemporaryDirectory() as tmp:
        for mesh in MESHES:
            for name, flags in BASES:
                r = run(mesh, flags, order, tmp)
                if isinstance(r, str):
                    lines.append(f"| {mesh} | {name} | " + " | ".join("-" for _ in shown) + f" | failed: {r} | - |")
                    print(lines[-1], flush=True)
                    continue
                errors = {e["order"]: e for e in r["errors_by_order"]}
                cells = [f"{errors[o]['mean_relative']:.4f} / {errors[o]['max_relative']:.3f}" for o in shown]
                b = r.get("boundary_max_relative")
                boundary = "closed" if b is None else f"{b:.4f}"
                lines.append(f"| {mesh} (Z* {r['z_star']:.3f}) | {name} | " + " | ".join(cells) + f" | {boundary} | {r['fit_seconds']:.2f} |")
                print(lines[-1], flush=True)
    out = ROOT / "benchmarks/results/scha_table.md"
    out.write_text("\n".join(lines) + "\n")
    print(f"written to {out}")


if __name__ == "__main__":
    main()
