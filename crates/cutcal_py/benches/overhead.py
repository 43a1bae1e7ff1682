"""Call overhead of the Python face of the extended Oxley model (issue 14).

    RAYON_NUM_THREADS=1 python crates/cutcal_py/benches/overhead.py [N]

Compares, per condition, the wall time seen from Python with the time spent in the Rust loop of
`predict_many` (its `rust_seconds`), on one thread so that both count the same work:
- batch: one `predict_many` call over N conditions (AISI 1045, 150-250 m/min, Lalwani's JC);
- single: one `predict_many` call per condition (N calls of one condition);
- predict: one `predict(material, jc, [test])` call per condition (the CLI's JSON document).
Prints microseconds per condition and the overhead above Rust. Timing only: no assertion here.
"""

import os
import sys
import time
from pathlib import Path

import numpy as np

import cutcal

ROOT = Path(__file__).resolve().parents[3]


def main(n: int) -> None:
    m = cutcal.Material.from_toml(ROOT / "fixtures/materials/aisi1045.toml")
    jc = cutcal.JcParams.from_toml(ROOT / "fixtures/jc/aisi1045_jaspers2002.toml")
    speeds = np.linspace(150.0, 250.0, n)
    cutcal.predict_many(m, jc, speeds[:4], 0.15, 1.6, -7.0)  # warm-up

    t0 = time.perf_counter()
    out = cutcal.predict_many(m, jc, speeds, 0.15, 1.6, -7.0)
    batch_wall = (time.perf_counter() - t0) / n
    batch_rust = out["rust_seconds"] / n
    assert out["converged"].all()

    rust_single = 0.0
    t0 = time.perf_counter()
    for s in speeds:
        rust_single += cutcal.predict_many(m, jc, s, 0.15, 1.6, -7.0)["rust_seconds"]
    single_wall = (time.perf_counter() - t0) / n
    rust_single /= n

    tests = [cutcal.CuttingTest(str(i), float(s), 0.15, 1.6, -7.0) for i, s in enumerate(speeds)]
    t0 = time.perf_counter()
    for t in tests:
        cutcal.predict(m, jc, [t])
    predict_wall = (time.perf_counter() - t0) / n

    us = 1e6
    print(f"conditions: {n}, RAYON_NUM_THREADS={os.environ.get('RAYON_NUM_THREADS', '(all cores)')}")
    print(f"Rust time per condition in predict_many:       {batch_rust * us:9.1f} us")
    print(f"batch predict_many, per condition:             {batch_wall * us:9.1f} us  (+{(batch_wall - batch_rust) * us:.2f} us)")
    print(f"predict_many of one condition, per call:       {single_wall * us:9.1f} us  (+{(single_wall - rust_single) * us:.2f} us)")
    print(f"predict(material, jc, [test]), per call:       {predict_wall * us:9.1f} us  (+{(predict_wall - rust_single) * us:.2f} us)")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 200)
