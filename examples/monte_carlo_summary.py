"""Statistics of the two-ball tolerance Monte Carlo (examples/two_ball_monte_carlo.toml).

    python examples/monte_carlo_summary.py ballbench-sweeps/two-ball-monte-carlo [histogram.png]

Prints how often the two balls press on each other (F_B2B > 0), quantiles of F_B2B and of the friction
increase (total / ball-to-groove loss of the free balls - 1), and the failed cases by reason.
"""
import sys
from collections import Counter
from pathlib import Path

import numpy as np

from ballbench.validation.sweep import read_results

QUANTILES = (0.5, 0.9, 0.99, 0.999)


def summary(directory: str) -> dict:
    result = read_results(directory)
    ok = np.array([not e for e in result["error"]])
    force = result["b2b_force"][ok]
    increase = result["friction_increase"][ok]
    contact = force > 1e-9 * 100.0  # N, relative to the 100 N load
    return {"cases": int(result["case"].size), "converged": int(ok.sum()),
            "failed": dict(Counter(e.split(":")[0] for e in result["error"] if e)),
            "share_in_contact": float(contact.mean()),
            "b2b_force_quantiles_N": {q: float(np.quantile(force, q)) for q in QUANTILES},
            "b2b_force_max_N": float(force.max()),
            "friction_increase_quantiles": {q: float(np.quantile(increase, q)) for q in QUANTILES},
            "friction_increase_mean": float(increase.mean()),
            "friction_increase_max": float(increase.max()),
            "result": result, "ok": ok}


def main(directory: str, target: str | None = None) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    s = summary(directory)
    for key, value in s.items():
        if key not in ("result", "ok"):
            print(f"{key}: {value}")
    result, ok = s["result"], s["ok"]
    figure, (left, right) = plt.subplots(1, 2, figsize=(10, 4), layout="constrained")
    left.hist(result["b2b_force"][ok], bins=100, log=True)
    left.set_xlabel("F_B2B [N]")
    right.hist(100 * result["friction_increase"][ok], bins=100, log=True)
    right.set_xlabel("friction increase [%]")
    for ax in (left, right):
        ax.set_ylabel("cases")
    figure.suptitle(f"{s['converged']} of {s['cases']} cases; balls pressed together in "
                    f"{100 * s['share_in_contact']:.1f} %")
    target = target or str(Path(directory) / "histogram.png")
    figure.savefig(target, dpi=120)
    print(target)


if __name__ == "__main__":
    main(*sys.argv[1:3])
