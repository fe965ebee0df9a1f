"""Audit every IFC model in a folder for three robot profiles on a Dask cluster.

Usage: python examples/audit_folder.py FOLDER [--scheduler tcp://host:8786] [--workers 2]
                                       [--csv audit.csv]

Without --scheduler a LocalCluster with --workers threaded workers runs here; with it, the
same code runs on that cluster (the workers must have poinav installed and read FOLDER, or
pass --ship-bytes to send the files' bytes). Prints one row per model and profile: door
passages by status and spaces reachable; --csv writes the table.
"""

import argparse
import sys
from pathlib import Path

import poinav.dask
from distributed import Client, LocalCluster

PROFILES = Path(__file__).resolve().parent / "profiles"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folder")
    ap.add_argument("--scheduler", help="address of a Dask scheduler (default: a LocalCluster)")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--csv")
    ap.add_argument("--ship-bytes", action="store_true")
    args = ap.parse_args()
    files = sorted(Path(args.folder).glob("*.ifc"))
    if not files:
        print(f"error: no .ifc files in {args.folder}", file=sys.stderr)
        return 2
    profiles = ["paper", PROFILES / "compact-robot.toml", PROFILES / "wide-cart.toml"]
    if args.scheduler:
        client = Client(args.scheduler)
    else:
        client = Client(LocalCluster(n_workers=args.workers, threads_per_worker=1,
                                     processes=False, dashboard_address=None))
    with client:
        table = poinav.dask.audit_files(client, files, profiles=profiles,
                                        ship_bytes=args.ship_bytes)
    table["file"] = table["file"].map(lambda f: Path(f).name)
    print(table.to_string(index=False))
    if args.csv:
        table.to_csv(args.csv, index=False)
    return 0


if __name__ == "__main__":
    sys.exit(main())
