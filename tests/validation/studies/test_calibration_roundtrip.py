"""validation.studies.calibration.roundtrip: the synthetic calibration round trip (interval coverage over seeds)."""


def test_intervals_cover_the_truth_in_at_least_90_percent_of_seeds():
    from ballbench.validation.studies.calibration.roundtrip import coverage, synthetic_truth

    shares = coverage(range(100), synthetic_truth())
    assert set(shares) == {"hertz_constant", "bulk_compliance", "psi", "mu", "mu_speed_slope", "k_f"}
    for name, share in shares.items():
        assert share >= 0.90, f"{name}: 95 % interval covers the truth in {100 * share:.0f} % of 100 seeds"
