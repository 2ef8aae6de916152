"""Statistics of the whole-screw Monte Carlo (examples/whole_screw_monte_carlo.toml).

    python examples/whole_screw_summary.py ballbench-sweeps/whole-screw-monte-carlo

Prints the share of screws with any ball-to-ball contact, quantiles of the peak and mean B2B friction torque on
the nut and of the torque increase (B2B / ball-to-groove torque), and the failed screws by reason.
"""
import sys
from collections import Counter

import numpy as np

from ballbench.validation.sweep import read_results

QUANTILES = (0.1, 0.5, 0.9, 0.99)


def summary(directory: str) -> dict:
    result = read_results(directory)
    ok = np.array([not e for e in result["error"]])
    out = {"screws": int(result["case"].size), "converged": int(ok.sum()),
           "failed": dict(Counter(e.split(":")[0] for e in result["error"] if e)),
           "share_with_b2b": float(np.mean(result["max_b2b_force"][ok] > 0.0))}
    for name, unit in (("peak_b2b_torque", "N m"), ("mean_b2b_torque", "N m"), ("peak_increase", "%"),
                       ("mean_increase", "%"), ("max_b2b_force", "N")):
        values = result[name][ok]
        out[f"{name} [{unit}]"] = {"mean": float(values.mean()), "max": float(values.max()),
                                   **{f"q{q:g}": float(np.quantile(values, q)) for q in QUANTILES}}
    return out


if __name__ == "__main__":
    for key, value in summary(sys.argv[1]).items():
        print(f"{key}: {value}")
