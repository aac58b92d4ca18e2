"""A stand-in for bpy.types.UILayout that records what a panel's draw (or draw_header) puts
on screen: each property with its label and whether it is drawn active (not greyed out: its
own layout and every enclosing one active, as Blender decides), each label, each heading.
Panels are drawn outside a real region this way in both Blenders (the bpy wheel has none)."""

from __future__ import annotations

from dataclasses import dataclass, field
from types import SimpleNamespace
from typing import Any


@dataclass
class Drawn:
    """One property a panel drew: its name, the text it was drawn with (None: the property's
    own label) and whether it was active."""

    name: str
    text: str | None
    active: bool


@dataclass
class PanelRecord:
    props: list[Drawn] = field(default_factory=list)
    labels: list[str] = field(default_factory=list)
    headings: list[str] = field(default_factory=list)

    def names(self) -> list[str]:
        return [p.name for p in self.props]

    def prop(self, name: str) -> Drawn:
        """The one drawing of `name` (AssertionError when drawn other than once)."""
        found = [p for p in self.props if p.name == name]
        assert len(found) == 1, (name, self.props)
        return found[0]


class RecordingLayout:
    def __init__(self, record: PanelRecord, parent: RecordingLayout | None = None) -> None:
        self.record = record
        self.parent = parent
        self.active = True
        self.enabled = True
        self.use_property_split = False
        self.use_property_decorate = True

    def is_active(self) -> bool:
        return self.active and (self.parent is None or self.parent.is_active())

    def _child(self, heading: str = "", **_: Any) -> RecordingLayout:
        if heading:
            self.record.headings.append(heading)
        return RecordingLayout(self.record, self)

    def column(self, heading: str = "", **options: Any) -> RecordingLayout:
        return self._child(heading, **options)

    def row(self, heading: str = "", **options: Any) -> RecordingLayout:
        return self._child(heading, **options)

    def prop(self, data: Any, name: str, text: str | None = None, **_: Any) -> None:
        assert hasattr(data, name), name  # a typo in a property name fails here
        self.record.props.append(Drawn(name, text, self.is_active()))

    def label(self, text: str = "", **_: Any) -> None:
        self.record.labels.append(text)

    def separator(self, **_: Any) -> None:
        pass


def draw_panel(panel: type, scene: Any, header: bool = False) -> PanelRecord:
    """What panel class `panel` draws for `scene` (its draw_header when `header`)."""
    record = PanelRecord()
    fake = SimpleNamespace(layout=RecordingLayout(record))
    context = SimpleNamespace(scene=scene, engine="STRATUM")
    (panel.draw_header if header else panel.draw)(fake, context)
    return record
