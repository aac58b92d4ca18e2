"""When the Rendered viewport redraws (engine/viewport.py _redraw_views, a bpy.app.timers
callback): while the frame drawn last shows an older scene or view than the session renders,
the timer polls the session every FAST_POLL_SECONDS and asks for the redraw as soon as the first
new frame is there, for at most FAST_POLL_LIMIT; otherwise it redraws once per REDRAW_SECONDS.
The session is a stand-in with a generation and a frame, so the test controls both.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import pytest


@dataclass
class _Frame:
    generation: int


class _Session:
    """What _redraw_views reads of a ViewportSession."""

    def __init__(self, generation: int) -> None:
        self.generation = generation
        self.next_frame: _Frame | None = None
        self.error: Exception | None = None

    def frame(self) -> _Frame | None:
        if self.error is not None:
            raise self.error
        return self.next_frame

    def free(self) -> None:
        pass


@pytest.fixture
def viewport(stratum_addon: Any) -> Any:
    from stratum.engine import viewport

    return viewport


def _state(viewport: Any, drawn: int, now: int) -> Any:
    state = viewport.ViewportState()
    state.session.free()
    state.session = _Session(now)
    state.drawn_generation = drawn
    state.redraw_pending = True
    return state


def test_a_stale_frame_is_replaced_as_soon_as_the_new_one_is_there(viewport: Any) -> None:
    state = _state(viewport, drawn=3, now=4)
    assert viewport._redraw_interval(state) == viewport.FAST_POLL_SECONDS
    # The session still shows generation 3: poll again soon, keep the redraw pending.
    state.session.next_frame = _Frame(3)
    assert viewport._redraw_views(state) == viewport.FAST_POLL_SECONDS
    assert state.redraw_pending
    # Generation 4's first frame: redraw now, once.
    state.session.next_frame = _Frame(4)
    assert viewport._redraw_views(state) is None
    assert not state.redraw_pending


def test_a_frame_of_the_current_generation_redraws_at_the_refining_rate(viewport: Any) -> None:
    state = _state(viewport, drawn=4, now=4)
    assert viewport._redraw_interval(state) == viewport.REDRAW_SECONDS
    assert viewport._redraw_views(state) is None
    assert not state.redraw_pending


def test_fast_polling_ends_after_its_limit(viewport: Any, monkeypatch: pytest.MonkeyPatch) -> None:
    state = _state(viewport, drawn=3, now=4)
    clock = [100.0]
    monkeypatch.setattr(viewport.time, "monotonic", lambda: clock[0])
    assert viewport._redraw_views(state) == viewport.FAST_POLL_SECONDS  # stale since 100 s
    clock[0] += viewport.FAST_POLL_LIMIT
    assert viewport._redraw_interval(state) == viewport.REDRAW_SECONDS
    # No new frame yet (a big scene's first frame), but the view is redrawn at the normal rate.
    assert viewport._redraw_views(state) is None
    assert not state.redraw_pending
    # A later change makes a new stale generation: fast again, timed from that change.
    state.session.generation = 5
    assert viewport._redraw_interval(state) == viewport.FAST_POLL_SECONDS


def test_a_failing_session_is_left_to_the_redraw_to_report(viewport: Any) -> None:
    state = _state(viewport, drawn=3, now=4)
    state.session.error = RuntimeError("renderer failed")
    assert viewport._redraw_views(state) is None
    assert not state.redraw_pending


def test_a_freed_viewport_stops_the_timer(viewport: Any) -> None:
    state = _state(viewport, drawn=3, now=4)
    state.freed = True
    assert viewport._redraw_views(state) is None
    assert not state.redraw_pending
