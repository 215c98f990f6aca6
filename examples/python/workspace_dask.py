"""Spreads a workspace sampling over a Dask cluster: each task solves a contiguous range of sample
indices with pcr.sample_workspace(first_sample=...), and a sample depends only on (seed, index), so the
points are the same however the range is split - across threads, processes or machines.

    python3 workspace_dask.py models/stewart_gough.urdf --samples 1000 --chunk 100 --out points.npy
    python3 workspace_dask.py MODEL --scheduler tcp://host:8786 ...   # an existing cluster

Without --scheduler it starts a LocalCluster of --workers processes. Writes an (N, 3) array of the first
platform's positions [m] in sample order, NaN rows for samples that did not converge.
"""
import argparse

import numpy as np
from dask.distributed import Client, LocalCluster

import pcr


def solve_range(model_path, seed, first, count):
    """Runs in a worker: loads the model there (models are not pickled) and solves its samples."""
    model = pcr.load_model(model_path)
    result = pcr.sample_workspace(model, samples=count, seed=seed, first_sample=first)
    return [(s.index, s.platforms[0].position.tolist() if s.converged else None) for s in result.samples]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("model")
    parser.add_argument("--samples", type=int, default=100)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--chunk", type=int, default=25, help="samples per task")
    parser.add_argument("--workers", type=int, default=2, help="LocalCluster processes")
    parser.add_argument("--scheduler", help="address of a running Dask scheduler")
    parser.add_argument("--out", default="workspace_points.npy")
    args = parser.parse_args()

    cluster = None if args.scheduler else LocalCluster(n_workers=args.workers, threads_per_worker=1,
                                                       dashboard_address=None)
    with Client(args.scheduler or cluster) as client:
        tasks = [client.submit(solve_range, args.model, args.seed, first, min(args.chunk, args.samples - first))
                 for first in range(0, args.samples, args.chunk)]
        points = np.full((args.samples, 3), np.nan)
        for chunk in client.gather(tasks):
            for index, position in chunk:
                if position is not None:
                    points[index] = position
    if cluster is not None:
        cluster.close()
    np.save(args.out, points)
    print("%d samples, %d converged -> %s" % (args.samples, int(np.sum(~np.isnan(points[:, 0]))), args.out))


if __name__ == "__main__":
    main()
