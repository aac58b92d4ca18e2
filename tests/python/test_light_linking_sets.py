"""export/light_linking.py against Blender's depsgraph_light_linking.cc rules, on stand-ins for
the bpy objects it reads (the module docstring lists the rules)."""

from __future__ import annotations

from dataclasses import dataclass, field
from types import SimpleNamespace
from typing import Any

from stratum.export.light_linking import ALL_SETS, linking_sets


class _Id:
    def as_pointer(self) -> int:
        return id(self)

    @property
    def original(self) -> Any:
        return self


@dataclass(eq=False)
class FakeObject(_Id):
    name: str
    light_linking: Any = field(default_factory=lambda: SimpleNamespace(
        receiver_collection=None, blocker_collection=None))


def _entry(state: str) -> Any:
    return SimpleNamespace(light_linking=SimpleNamespace(link_state=state))


@dataclass(eq=False)
class FakeCollection(_Id):
    objects: list[FakeObject] = field(default_factory=list)
    collection_objects: list[Any] = field(default_factory=list)
    children: list[FakeCollection] = field(default_factory=list)
    collection_children: list[Any] = field(default_factory=list)

    def link(self, ob: FakeObject, state: str = "INCLUDE") -> FakeCollection:
        self.objects.append(ob)
        self.collection_objects.append(_entry(state))
        return self

    def add_child(self, child: FakeCollection, state: str) -> FakeCollection:
        self.children.append(child)
        self.collection_children.append(_entry(state))
        return self

    @property
    def all_objects(self) -> list[FakeObject]:
        seen: dict[int, FakeObject] = {}
        for child in self.children:
            for ob in child.all_objects:
                seen.setdefault(id(ob), ob)
        for ob in self.objects:
            seen.setdefault(id(ob), ob)
        return list(seen.values())


def _depsgraph(*objects: FakeObject) -> Any:
    return SimpleNamespace(objects=list(objects))


def _lit(sets: Any, emitter: FakeObject, receiver: FakeObject, parent: Any = None) -> bool:
    links = sets.links(receiver, parent)
    return bool((sets.links(emitter).light_set_membership >> links.receiver_light_set) & 1)


def test_an_include_entry_lights_only_the_listed_objects() -> None:
    a, b, lamp = FakeObject("A"), FakeObject("B"), FakeObject("lamp")
    lamp.light_linking.receiver_collection = FakeCollection().link(a, "INCLUDE")
    sets = linking_sets(_depsgraph(a, b, lamp))
    assert sets.links(a).receiver_light_set == 1
    assert sets.links(b).receiver_light_set == 0
    assert sets.links(lamp).light_set_membership == 0b10
    assert _lit(sets, lamp, a) and not _lit(sets, lamp, b)
    # An emitter without a collection lights everything.
    assert sets.links(a).light_set_membership == ALL_SETS


def test_an_exclude_entry_lights_everything_else() -> None:
    a, b, sun = FakeObject("A"), FakeObject("B"), FakeObject("sun")
    sun.light_linking.blocker_collection = FakeCollection().link(b, "EXCLUDE")
    sets = linking_sets(_depsgraph(a, b, sun))
    assert sets.links(b).blocker_shadow_set == 1
    assert sets.links(sun).shadow_set_membership == ALL_SETS & ~0b10
    assert sets.links(sun).light_set_membership == ALL_SETS
    assert sets.links(b).receiver_light_set == 0


def test_emitters_sharing_a_collection_share_its_sets() -> None:
    a, b, c = FakeObject("A"), FakeObject("B"), FakeObject("C")
    lamp1, lamp2, lamp3 = FakeObject("l1"), FakeObject("l2"), FakeObject("l3")
    shared = FakeCollection().link(a, "INCLUDE").link(b, "EXCLUDE")
    lamp1.light_linking.receiver_collection = shared
    lamp2.light_linking.receiver_collection = shared
    lamp3.light_linking.receiver_collection = FakeCollection().link(b, "INCLUDE")
    sets = linking_sets(_depsgraph(a, b, c, lamp1, lamp2, lamp3))
    assert sets.links(lamp1) == sets.links(lamp2)
    # A: lit by l1/l2 only; B: excluded by l1/l2, included by l3; C: default set.
    assert _lit(sets, lamp1, a) and not _lit(sets, lamp3, a)
    assert not _lit(sets, lamp1, b) and _lit(sets, lamp3, b)
    assert not _lit(sets, lamp1, c) and not _lit(sets, lamp3, c)
    assert len({sets.links(o).receiver_light_set for o in (a, b, c)}) == 3


def test_nested_objects_take_the_first_level_state_and_later_entries_win() -> None:
    a, b, lamp = FakeObject("A"), FakeObject("B"), FakeObject("lamp")
    inner = FakeCollection().link(a, "INCLUDE")  # its own state is not read
    middle = FakeCollection().add_child(inner, "INCLUDE").link(b)
    top = FakeCollection().add_child(middle, "EXCLUDE").link(b, "INCLUDE")
    lamp.light_linking.receiver_collection = top
    sets = linking_sets(_depsgraph(a, b, lamp))
    assert not _lit(sets, lamp, a)  # EXCLUDE from the first-level child entry
    assert _lit(sets, lamp, b)  # the object entry comes after the child's


def test_instances_take_their_instancer_set_when_it_has_one() -> None:
    a, instancer, plain, lamp = (FakeObject(n) for n in ("A", "inst", "plain", "lamp"))
    lamp.light_linking.receiver_collection = FakeCollection().link(instancer, "EXCLUDE")
    sets = linking_sets(_depsgraph(a, instancer, plain, lamp))
    assert not _lit(sets, lamp, a, parent=instancer)
    assert _lit(sets, lamp, a, parent=plain)


def test_no_linking_and_blender_3_read_nothing() -> None:
    assert linking_sets(_depsgraph(FakeObject("A"))) is None
    assert linking_sets(SimpleNamespace(objects=[SimpleNamespace(original=object())])) is None


def test_sets_past_63_stay_default() -> None:
    lamps, receivers = [], []
    for i in range(64):
        ob, lamp = FakeObject(f"r{i}"), FakeObject(f"l{i}")
        lamp.light_linking.receiver_collection = FakeCollection().link(ob, "INCLUDE")
        lamps.append(lamp)
        receivers.append(ob)
    sets = linking_sets(_depsgraph(*receivers, *lamps))
    ids = [sets.links(ob).receiver_light_set for ob in receivers]
    assert ids[:63] == list(range(1, 64)) and ids[63] == 0
    assert sets.links(lamps[63]).light_set_membership == ALL_SETS  # its set overflowed
