"""One frame's samples over a Dask cluster (stratum.cli.distributed): the merged image is
bit-identical to one render of all the samples, for every sampler."""

from __future__ import annotations

import tempfile
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from conftest import lit_quad_scene

SIZE, SAMPLES = 32, 16


def _frame(native: Any, sampler: str) -> Any:
    from stratum.cli.distributed import Frame

    scene = lit_quad_scene(native, light_radius=0.1, background=0.2)
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "scene.stratum"
        scene.save(path)
        scene.close()
        data = path.read_bytes()
    return Frame(data, {"width": SIZE, "height": SIZE, "samples": SAMPLES, "seed": 7,
                        "sampler": sampler, "threads": 1})


def _one_machine(native: Any, frame: Any) -> np.ndarray:
    """A plain render of all the samples: no sample subset, no sums read or added."""
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "scene.stratum"
        path.write_bytes(frame.scene_file)
        scene = native.Scene.load(path)
    with scene, native.Renderer(scene, **frame.settings) as renderer:
        renderer.start()
        while not renderer.wait(1000):
            pass
        return renderer.read_pixels().copy()


def test_split_samples_covers_every_index_once_in_order() -> None:
    from stratum.cli.distributed import split_samples

    assert split_samples(16, 2) == [(0, 8), (8, 8)]
    assert split_samples(10, 3) == [(0, 4), (4, 3), (7, 3)]
    assert split_samples(2, 5) == [(0, 1), (1, 1)]
    with pytest.raises(ValueError):
        split_samples(0, 2)


def test_a_local_cluster_of_two_workers_renders_the_one_machine_image_bit_for_bit(
        native: Any) -> None:
    distributed = pytest.importorskip("distributed")
    from stratum.cli.distributed import render_on_cluster

    samplers = [e.name for e in native.registry("sampler")]
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        for sampler in samplers:
            frame = _frame(native, sampler)
            renderer, notices = render_on_cluster(client, frame)
            with renderer:
                merged = renderer.read_pixels()
            # The same frame again at once: its data must not be lost with the first's.
            again, _ = render_on_cluster(client, frame)
            with again:
                assert again.read_pixels().tobytes() == merged.tobytes()
            expected = _one_machine(native, frame)
            assert notices == []
            assert merged.tobytes() == expected.tobytes(), sampler
            # Not a trivially equal image: the quad, the light and the noise are in it.
            assert np.ptp(merged[0::4]) > 0.1


def test_a_worker_failure_and_an_unreachable_scheduler_are_named(
        native: Any, monkeypatch: pytest.MonkeyPatch) -> None:
    distributed = pytest.importorskip("distributed")
    from stratum.cli.distributed import DistributedError, Frame, connect, render_on_cluster

    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        broken = Frame(b"not a scene file", {"width": 8, "height": 8, "samples": 2})
        with pytest.raises(DistributedError, match=r"a worker failed rendering samples \[0, 2\)"):
            render_on_cluster(client, broken)
        adaptive = Frame(b"", {"width": 8, "height": 8, "samples": 2, "use_adaptive_sampling": 1})
        with pytest.raises(DistributedError, match="use_adaptive_sampling=0"):
            render_on_cluster(client, adaptive)
    monkeypatch.setattr("stratum.cli.distributed.CONNECT_TIMEOUT", 2)
    with pytest.raises(DistributedError, match="cannot reach the Dask scheduler"):
        connect("tcp://127.0.0.1:9")
    with pytest.raises(DistributedError, match="local:N"):
        connect("local:zero")


def test_the_command_line_renders_a_blend_over_local_clusters_of_one_and_two_workers(
        native: Any, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """`stratum render --scheduler local:N`: Blender exports, workers render; one worker (the
    whole range, one machine) and two write the same pixels. An unreachable scheduler exits 1."""
    pytest.importorskip("distributed")
    openexr = pytest.importorskip("OpenEXR")
    from stratum.cli import main
    from stratum.cli.blender_process import blender_executable

    if blender_executable() is None:
        pytest.skip("Blender not found")
    blend = Path(__file__).resolve().parents[2] / "scenes" / "cornell_box.blend"
    outputs = []
    for workers in (1, 2):
        out = tmp_path / f"local{workers}.exr"
        assert main(["render", str(blend), "-o", str(out), "--samples", "4", "--resolution",
                     "16x16", "--sampler", "zsobol", "--scheduler", f"local:{workers}"]) == 0
        # The pixels (the EXR header holds the time of writing).
        channels = openexr.File(str(out)).channels()
        outputs.append({name: np.asarray(c.pixels).tobytes() for name, c in channels.items()})
    assert list(outputs[0]) == ["RGBA"]
    assert outputs[0] == outputs[1]
    monkeypatch.setattr("stratum.cli.distributed.CONNECT_TIMEOUT", 2)
    assert main(["render", str(blend), "-o", str(tmp_path / "x.exr"), "--scheduler",
                 "tcp://127.0.0.1:9"]) == 1
