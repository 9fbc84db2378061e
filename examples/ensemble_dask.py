"""An ensemble of packings (statistical volume elements) on Dask.

Each seed of a scene is one independent Dask task; their summaries are gathered into
one table: packing fraction, the KS distances of every phase's diameters and aspect
ratios against their laws, and the timings.

    # on this machine (a LocalCluster of 2 one-thread workers):
    python examples/ensemble_dask.py configs/grains.toml --seeds 8
    # on a running cluster (dask-scheduler, dask-jobqueue's SLURMCluster, ...):
    python examples/ensemble_dask.py configs/grains.toml --seeds 64 --scheduler tcp://host:8786

Needs `pip install ./python "dask[distributed]"`. The scene travels to the workers as
TOML text, so they need the package but not the file; the workers each pack with
`--threads` threads (default 1: one realisation per core scales best).
"""

from __future__ import annotations

import argparse
import csv
import os
import sys
from pathlib import Path
from typing import Any

import grainpack as gp


def realisation(scene_toml: str, seed: int, threads: int, out: str | None) -> dict[str, Any]:
    """One packing of the scene with `seed`, on a worker: its summary, and its files
    written into `out/seed-<seed>` when `out` is given."""
    scene = gp.Scene.from_toml(scene_toml)
    packing = gp.pack(scene, seed=seed, threads=threads, progress=False)
    if out is not None:
        packing.write(Path(out) / f"seed-{seed}")
    return packing.summary


def row(summary: dict[str, Any]) -> dict[str, Any]:
    """The table row of one summary."""
    r: dict[str, Any] = {
        "seed": summary["seed"],
        "grains": summary["grains"],
        "packing_fraction": summary["packing_fraction"],
        "target_fraction": summary["target_fraction"],
        "stop_reason": summary["stop_reason"],
        "min_mu2": summary["min_mu2"],
    }
    for phase in summary["phases"]:
        for quantity in ("diameter", "aspect_ratio"):
            stats = phase.get(quantity) or {}
            r[f"{phase['name']}.{quantity}.ks"] = stats.get("ks_distance")
    r["packing_seconds"] = summary["timings"]["packing"]
    r["total_seconds"] = summary["timings"]["total"]
    return r


def run_ensemble(
    scene_path: str | os.PathLike[str],
    seeds: list[int],
    client: Any,
    threads: int = 1,
    out: str | None = None,
) -> list[dict[str, Any]]:
    """Packs `scene_path` once per seed as Dask tasks on `client`; the table's rows in
    seed order. The scene is validated here first, so a bad file fails before any task
    is submitted."""
    gp.Scene.from_toml(Path(scene_path))
    text = Path(scene_path).read_text()
    futures = [
        client.submit(realisation, text, seed, threads, out, key=f"pack-seed-{seed}", pure=False)
        for seed in seeds
    ]
    return [row(s) for s in client.gather(futures)]


def write_table(rows: list[dict[str, Any]], stream: Any) -> None:
    writer = csv.DictWriter(stream, fieldnames=list(rows[0]))
    writer.writeheader()
    writer.writerows(rows)


def main(argv: list[str] | None = None) -> list[dict[str, Any]]:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("scene", help="scene file (TOML)")
    parser.add_argument("--seeds", type=int, default=4, help="number of realisations (seeds 1..N)")
    parser.add_argument("--first-seed", type=int, default=1)
    parser.add_argument("--scheduler", help="address of a running Dask scheduler (default: a LocalCluster)")
    parser.add_argument("--workers", type=int, default=2, help="LocalCluster workers (default 2)")
    parser.add_argument("--threads", type=int, default=1, help="threads per realisation (default 1)")
    parser.add_argument("--out", help="also write each realisation's files into OUT/seed-N")
    parser.add_argument("--table", help="write the table as CSV here (default: standard output)")
    args = parser.parse_args(argv)

    from dask.distributed import Client, LocalCluster

    seeds = list(range(args.first_seed, args.first_seed + args.seeds))
    if args.scheduler:
        with Client(args.scheduler) as client:
            rows = run_ensemble(args.scene, seeds, client, args.threads, args.out)
    else:
        with LocalCluster(
            n_workers=args.workers, threads_per_worker=1, processes=True, dashboard_address=None
        ) as cluster, Client(cluster) as client:
            rows = run_ensemble(args.scene, seeds, client, args.threads, args.out)
    if args.table:
        with open(args.table, "w", newline="") as f:
            write_table(rows, f)
    else:
        write_table(rows, sys.stdout)
    return rows


if __name__ == "__main__":
    main()
