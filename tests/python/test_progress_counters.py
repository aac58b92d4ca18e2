"""The render's named progress counters through the binding (Renderer.progress().counters,
stratum_renderer_progress_counter): every counter the library lists, by name; an index outside
the list refused naming it; path guiding's tree growing pass after pass; 0 for the features a
render does not use."""

from __future__ import annotations

import ctypes
import itertools
from typing import Any

NAMES = ["light_tree.seconds", "light_tree.bytes", "radiosity.patches", "radiosity.bytes",
         "radiosity.seconds", "radiosity.iterations", "guiding.nodes", "guiding.bytes"]


def _render(native: Any, scene: Any, **settings: Any) -> Any:
    with native.Renderer(scene, width=32, height=32, **settings) as renderer:
        renderer.start()
        while not renderer.wait(100):
            pass
        return renderer.progress()


def test_progress_holds_every_counter_by_name(native: Any, tiny_scene: Any) -> None:
    with native.Renderer(tiny_scene, width=8, height=8) as renderer:
        before = renderer.progress()
    # In the library's order, which only grows at the end.
    assert list(before.counters) == NAMES
    assert all(value == 0.0 for value in before.counters.values())
    assert before.counter("guiding.nodes") == 0.0


def test_an_index_outside_the_list_is_refused_naming_it(native: Any, tiny_scene: Any) -> None:
    lib = native.load_library()
    count = lib.stratum_progress_counter_count()
    assert count == len(NAMES)
    name = ctypes.c_char_p()
    value = ctypes.c_double(7.0)
    with native.Renderer(tiny_scene, width=8, height=8) as renderer:
        for index in (-1, count):
            status = lib.stratum_renderer_progress_counter(renderer.handle, index, ctypes.byref(name),
                                                           ctypes.byref(value))
            assert status == native.ERROR_INVALID_ARGUMENT
            assert lib.stratum_last_error().decode() == (
                f"stratum_renderer_progress_counter: progress counter index {index} out of range "
                f"[0, {count})")
            assert value.value == 7.0


def test_guiding_nodes_grow_pass_after_pass(native: Any, tiny_scene: Any) -> None:
    """The tree is reported after each training pass: more training samples (passes [0,1) [1,2)
    [2,4) [4,8) [8,16)) leave more nodes. The tree learns in a fixed order (tests/native
    test_determinism), so the counts are exact, whatever the thread count."""
    nodes = []
    for training in (1, 2, 4, 8, 16):
        p = _render(native, tiny_scene, samples=16, use_guiding=1, guiding_training_samples=training)
        assert p.counters["guiding.bytes"] > 0
        assert p.counters["radiosity.patches"] == p.counters["light_tree.bytes"] == 0.0
        nodes.append(p.counters["guiding.nodes"])
    assert all(a < b for a, b in itertools.pairwise(nodes)), nodes


def test_an_unguided_render_reports_no_tree(native: Any, tiny_scene: Any) -> None:
    p = _render(native, tiny_scene, samples=2)
    assert p.counters["guiding.nodes"] == p.counters["guiding.bytes"] == 0.0
