"""Reproduces the paper's Table 4 (JC identified from C38 test 3, original and enhanced DPZD) with
the `cutcal` Python module, and plots the Fig 4 zone fields with matplotlib when it is installed.

    python examples/table4.py [OUT_DIR]

Prints the table (cutcal against the paper, from fixtures/reference/paper_tables.toml) and writes
OUT_DIR/table4.json and, with matplotlib, OUT_DIR/fig4_fields.png (default OUT_DIR: target/examples).
Run headless with MPLBACKEND=Agg. Paths are relative to the repository root.
"""

import json
import sys
from pathlib import Path

try:
    import tomllib
except ImportError:  # Python < 3.11
    import tomli as tomllib

import cutcal

ROOT = Path(__file__).resolve().parents[1]
KEYS = ["a_mpa", "b_mpa", "n", "c", "m"]


def main(out_dir: Path) -> int:
    out_dir.mkdir(parents=True, exist_ok=True)
    paper = tomllib.loads((ROOT / "fixtures/reference/paper_tables.toml").read_text())["table4"]
    material = cutcal.Material.from_toml(ROOT / "fixtures/materials/c38.toml")
    tests = cutcal.read_tests(ROOT / "fixtures/tests/c38.csv", as_frame=False)
    test3 = next(t for t in tests if t.test == "3")

    results = {
        model: cutcal.identify(material, test3, model=model, preset="paper") for model in ("original", "enhanced")
    }
    print("Table 4, C38 test 3 (paper in brackets; * = at a bound)")
    print(f"{'model':<10}" + "".join(f"{k:>22}" for k in KEYS))
    table = {}
    for model, res in results.items():
        got = res.jc.to_dict()
        cells = []
        for k in KEYS:
            star = "*" if k in res.at_bounds else " "
            cells.append(f"{got[k]:>12.4g}{star}({paper[model][k]:>7.4g})")
        print(f"{model:<10}" + "".join(cells))
        table[model] = {"cutcal": {k: got[k] for k in KEYS}, "paper": paper[model], "at_bounds": res.at_bounds}
    (out_dir / "table4.json").write_text(json.dumps(table, indent=2) + "\n")

    try:
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed: no Fig 4 plot")
        return 0
    fields = results["enhanced"].fields
    panels = [("gamma", "shear strain gamma"), ("eps_dot_per_s", "eff. strain rate [1/s]"),
              ("tau_mpa", "shear stress tau [MPa]"), ("temperature_c", "temperature [degC]")]
    fig, axes = plt.subplots(2, 2, figsize=(9, 6), sharex=True)
    for ax, (key, label) in zip(axes.flat, panels):
        for model, res in results.items():
            ax.plot(res.fields["x_mm"], res.fields[key], label=model)
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    for ax in axes[1]:
        ax.set_xlabel("x [mm] (EF -h/2, AB 0, CD +h/2)")
    axes[0][0].legend()
    fig.suptitle("C38 test 3: DPZD zone fields (paper Fig 4), identified JC")
    fig.tight_layout()
    fig.savefig(out_dir / "fig4_fields.png", dpi=100)
    print(f"wrote {out_dir / 'fig4_fields.png'} ({len(fields['x_mm'])} points)")
    return 0


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "target/examples"))
