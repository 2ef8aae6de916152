"""Run a sweep on a Slurm or PBS batch cluster through dask-jobqueue.

    python examples/jobqueue_sweep.py examples/two_ball_monte_carlo.toml --jobs 50          # Slurm
    python examples/jobqueue_sweep.py examples/two_ball_monte_carlo.toml --jobs 50 --pbs    # PBS / Torque
    python examples/jobqueue_sweep.py examples/two_ball_monte_carlo.toml --dry-run          # print the job script

Each batch job runs one single-threaded dask worker (WORKER below: 1 core, 2 GB, 2 h); the scheduler runs in
this process, which also writes the results (Parquet parts, resumable; the Zarr Dataset for gridded sweeps).
Not run against a real batch system (none on the development machine): ``--dry-run`` builds the cluster object
and prints the job script it would submit, which tests/test_sweep.py checks without sbatch/qsub.
"""
import argparse
from pathlib import Path

WORKER = dict(cores=1, processes=1, memory="2GB", walltime="02:00:00")  # per batch job: one worker


def make_cluster(kind: str = "slurm", **options):
    """A dask-jobqueue cluster (``kind`` "slurm" or "pbs") with the WORKER settings (``options`` override)."""
    from dask_jobqueue import PBSCluster, SLURMCluster

    classes = {"slurm": SLURMCluster, "pbs": PBSCluster}
    if kind not in classes:
        raise ValueError(f"kind must be one of {sorted(classes)}, got {kind!r}")
    return classes[kind](**{**WORKER, **options})


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("spec")
    parser.add_argument("--out", help="output directory (default ./ballbench-sweeps/<name>)")
    parser.add_argument("--jobs", type=int, default=50, help="batch jobs = workers (default 50)")
    parser.add_argument("--pbs", action="store_true", help="PBS/Torque instead of Slurm")
    parser.add_argument("--dry-run", action="store_true", help="print the job script, submit nothing")
    args = parser.parse_args(argv)
    from dask.distributed import Client

    from ballbench.validation import sweep

    spec = sweep.load_spec(args.spec)
    cluster = make_cluster("pbs" if args.pbs else "slurm",
                           scheduler_options={"dashboard_address": "127.0.0.1:0"} if args.dry_run else None)
    try:
        if args.dry_run:
            print(cluster.job_script())
            return 0
        cluster.scale(jobs=args.jobs)
        with Client(cluster) as client:
            client.wait_for_workers(1)
            out = Path(args.out) if args.out else Path("ballbench-sweeps") / spec.name
            summary = sweep.run_sweep(spec, out, client=client)
        print(f"{spec.name}: {summary.computed} cases in {summary.wall_time_s:.1f} s ({summary.throughput:.1f} cases/s,"
              f" {summary.failed} failed); results: {out}")
    finally:
        cluster.close()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
