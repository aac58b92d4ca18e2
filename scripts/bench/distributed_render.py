"""One frame's samples over a Dask cluster (issue 15, target 6): the Cornell box captured once
through Blender, then rendered by a LocalCluster of 1 and of 2 worker processes, each worker
rendering with one thread, so that the speed-up is that of adding a machine. Prints the wall
times of the cluster render (send, render, sums back, merge; not the export or the cluster's
start), the speed-up, and whether the two merged images are the same bits; also written to
out/bench/distributed.json for the summary (summary.py).

    .venv/bin/python -m scripts.bench.distributed_render [--res 256] [--samples 64] [--repeats 2]
"""

from __future__ import annotations

import argparse
import os
import sys
import time

from stratum.cli.blender_process import blender_executable
from stratum.cli.distributed import Frame, export_blend, render_on_cluster

from scripts import REPO
from scripts.bench.results import write_section

# Worker processes import the add-on's package from this checkout too.
os.environ["PYTHONPATH"] = os.pathsep.join(
    [str(REPO / "addon")] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p])


def timed_render(frame: Frame, workers: int, repeats: int) -> tuple[float, bytes]:
    from distributed import Client, LocalCluster

    with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        client.wait_for_workers(workers)
        best, pixels = float("inf"), b""
        for _ in range(repeats):
            t0 = time.perf_counter()
            renderer, _ = render_on_cluster(client, frame)
            with renderer:
                pixels = renderer.read_pixels().tobytes()
            best = min(best, time.perf_counter() - t0)
    return best, pixels


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("--res", type=int, default=256)
    p.add_argument("--samples", type=int, default=64)
    p.add_argument("--repeats", type=int, default=2)
    args = p.parse_args()
    blender = blender_executable()
    if blender is None:
        print("bench.distributed_render: Blender not found", file=sys.stderr)
        return 1
    frame = export_blend(blender, REPO / "scenes" / "cornell_box.blend",
                         {"samples": args.samples}, (args.res, args.res))
    frame = Frame(frame.scene_file, frame.settings | {"threads": 1})
    one, one_pixels = timed_render(frame, 1, args.repeats)
    two, two_pixels = timed_render(frame, 2, args.repeats)
    same = "bit-identical" if one_pixels == two_pixels else "DIFFERENT"
    print(f"distributed Cornell box {args.res}x{args.res} {args.samples} spp, 1 thread per "
          f"worker: 1 worker {one:.2f} s, 2 workers {two:.2f} s, speed-up {one / two:.2f}x "
          f"(images {same})")
    write_section("distributed", {"res": args.res, "samples": args.samples,
                                  "one_worker": one, "two_workers": two,
                                  "bit_identical": one_pixels == two_pixels})
    return 0 if same == "bit-identical" else 1


if __name__ == "__main__":
    sys.exit(main())
