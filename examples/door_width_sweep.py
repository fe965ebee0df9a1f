"""Design sweep on a Dask cluster: the paper's doorway scenario on the test building with the
door of Room 2 from 0.70 to 1.30 m wide, for three robot profiles; prints each run's door
status and, per profile, the width from which the door is FULL_ACCESS.

Usage: python examples/door_width_sweep.py [--scheduler tcp://host:8786] [--workers 2]
                                           [--step 0.05] [--csv sweep.csv]
"""

import argparse
import sys
from pathlib import Path

import poinav.dask
from distributed import Client, LocalCluster

PROFILES = Path(__file__).resolve().parent / "profiles"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scheduler")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--step", type=float, default=0.05)
    ap.add_argument("--csv")
    args = ap.parse_args()
    n = round((1.30 - 0.70) / args.step)
    widths = [round(0.70 + k * args.step, 4) for k in range(n + 1)]
    profiles = ["paper", PROFILES / "compact-robot.toml", PROFILES / "wide-cart.toml"]
    if args.scheduler:
        client = Client(args.scheduler)
    else:
        client = Client(LocalCluster(n_workers=args.workers, threads_per_worker=1,
                                     processes=False, dashboard_address=None))
    with client:
        sweep = poinav.dask.door_width_sweep(client, widths, profiles=profiles)
    print(sweep.pivot(index="width_m", columns="profile", values="status").to_string())
    for profile, width in poinav.dask.flip_widths(sweep).items():
        print(f"{profile}: FULL_ACCESS from {width:.2f} m" if width else f"{profile}: never FULL_ACCESS")
    if args.csv:
        sweep.to_csv(args.csv, index=False)
    return 0


if __name__ == "__main__":
    sys.exit(main())
