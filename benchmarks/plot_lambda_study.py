"""Table and plot of benchmarks/results/lambda_study.json (written by the lambda_study example).

Writes benchmarks/results/lambda_study.md and lambda_study.png. Needs matplotlib (the venv
that benchmarks/meshlab_compare.sh creates has it).
"""
import json
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

here = pathlib.Path(__file__).resolve().parent / "results"
data = json.loads((here / "lambda_study.json").read_text())
lambdas = data["lambdas"]
runs = [r for r in data["runs"] if "error" not in r]
errors = [r for r in data["runs"] if "error" in r]
meshes = list(dict.fromkeys(r["mesh"] for r in data["runs"]))
refinements = sorted({r["area_refinement"] for r in data["runs"]})


def value(mesh, lam, refinement, key="mean_abs_d_area"):
    for r in runs:
        if r["mesh"] == mesh and r["lambda"] == lam and r["area_refinement"] == refinement:
            return r[key]
    return None


lines = ["# lambda study (closed surfaces)", ""]
lines.append("Mean |d_area| of the adaptive map for each lambda of the initial flattening (paper: 0.2).")
lines.append("`refined` is the default when this was measured (50 plain sweeps of face-level area refinement); `paper` is")
lines.append("`--area-refinement 0`. Folded faces are 0 in every run unless marked.")
lines.append("")
for refinement in refinements:
    label = "paper (no refinement)" if refinement == 0 else f"refined ({refinement} sweeps)"
    lines.append(f"## {label}")
    lines.append("")
    lines.append("| mesh | " + " | ".join(f"{lam:g}" for lam in lambdas) + " |")
    lines.append("|---|" + "---:|" * len(lambdas))
    for mesh in meshes:
        cells = []
        for lam in lambdas:
            v = value(mesh, lam, refinement)
            folds = value(mesh, lam, refinement, "flipped_faces")
            cells.append("-" if v is None else f"{v:.3f}" + ("" if not folds else f" ({folds} folds)"))
        lines.append(f"| {mesh} | " + " | ".join(cells) + " |")
    lines.append("")
for e in errors:
    lines.append(f"- {e['mesh']} lambda {e['lambda']} refinement {e['area_refinement']}: error {e['error']}")
(here / "lambda_study.md").write_text("\n".join(lines) + "\n")

fig, axes = plt.subplots(1, len(refinements), figsize=(6 * len(refinements), 4.5), sharey=True)
if len(refinements) == 1:
    axes = [axes]
for ax, refinement in zip(axes, refinements):
    for mesh in meshes:
        xs = [lam for lam in lambdas if value(mesh, lam, refinement) is not None]
        ax.plot(xs, [value(mesh, lam, refinement) for lam in xs], marker="o", label=mesh.replace("closed_", ""))
    ax.set_yscale("log")
    ax.set_xlabel("lambda")
    ax.axvline(0.2, color="grey", linestyle=":", linewidth=1)
    ax.set_title("paper's map" if refinement == 0 else f"with area refinement ({refinement} sweeps)")
    ax.grid(True, which="both", alpha=0.3)
axes[0].set_ylabel("mean |d_area|")
axes[-1].legend(fontsize=8)
fig.tight_layout()
fig.savefig(here / "lambda_study.png", dpi=120)
print(f"wrote {here / 'lambda_study.md'} and {here / 'lambda_study.png'}", file=sys.stderr)
