"""Light linking and shadow linking (Blender 4.0+): the sets Blender's depsgraph gives objects
(source/blender/depsgraph/intern/depsgraph_light_linking.cc), computed here from the bpy
properties, as Cycles reads them (intern/cycles/blender/light_linking.cpp).

* An emitter (a lamp or an emissive object) lists receivers in
  `object.light_linking.receiver_collection` and occluders in `blocker_collection`. Emitters
  with the same collection share one emitter-collection bit (at most 64 collections; later ones
  link nothing, as Blender's overflow).
* Each entry of the collection (`collection_objects[i]` / `collection_children[i]`, parallel to
  `objects` / `children`) has `light_linking.link_state` INCLUDE or EXCLUDE; objects in a child
  collection, at any depth, take the state of the first-level child entry. Later entries of the
  same object override earlier ones (children first, then objects, as Blender walks them).
* Each object listed anywhere gets a set (include mask, exclude mask) over the emitter bits;
  every distinct set an id 1..63 (0 is the default set of unlisted objects; sets past 63 stay
  0, as Blender's overflow). That id is the object's receiver_light_set (blocker_shadow_set).
* An emitter's light_set_membership (shadow_set_membership) is (the sets whose include mask
  has its bit, or all sets if none) minus the sets whose exclude mask has its bit; an emitter
  without a collection has all sets.
* Instances take their instancer's set when it has one (not 0), else their object's; memberships
  are always the instanced object's own.
* The world is not linkable. Blender 3.x has no `light_linking`: nothing is read there.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

ALL_SETS = (1 << 64) - 1
MAX_SET_ID = 63
MAX_EMITTER_COLLECTIONS = 64


@dataclass
class _Linking:
    """One kind of linking (light or shadow), as depsgraph_light_linking.cc's LinkingData and
    EmitterDataMap."""

    # Emitter collection pointer -> its bit (0 past the 64th: overflow).
    collection_bit: dict[int, int] = field(default_factory=dict)
    # Receiver (or blocker) pointer -> [include mask, exclude mask], in first-linked order.
    object_masks: dict[int, list[int]] = field(default_factory=dict)
    object_set: dict[int, int] = field(default_factory=dict)  # object pointer -> set id 1..63
    membership: dict[int, int] = field(default_factory=dict)  # collection pointer -> membership

    def add_emitter(self, collection: Any) -> None:
        key = collection.as_pointer()
        if key in self.collection_bit:
            return
        index = len(self.collection_bit)
        bit = 1 << index if index < MAX_EMITTER_COLLECTIONS else 0
        self.collection_bit[key] = bit
        if bit:
            for state, ob in _entries(collection):
                masks = self.object_masks.setdefault(ob.original.as_pointer(), [0, 0])
                if state == "INCLUDE":
                    masks[0] |= bit
                    masks[1] &= ~bit
                else:
                    masks[1] |= bit
                    masks[0] &= ~bit

    def end_build(self) -> None:
        set_ids: dict[tuple[int, int], int] = {}
        included: dict[int, int] = dict.fromkeys(self.collection_bit, 0)
        excluded: dict[int, int] = dict.fromkeys(self.collection_bit, 0)
        for ob, (include, exclude) in self.object_masks.items():
            set_id = set_ids.setdefault((include, exclude), len(set_ids) + 1)
            if set_id > MAX_SET_ID:
                continue
            self.object_set[ob] = set_id
            set_bit = 1 << set_id
            for collection, bit in self.collection_bit.items():
                if bit & include:
                    included[collection] |= set_bit
                if bit & exclude:
                    excluded[collection] |= set_bit
        for collection in self.collection_bit:
            self.membership[collection] = (included[collection] or ALL_SETS) & ~excluded[collection]


def _entries(collection: Any) -> Iterable[tuple[str, Any]]:
    """(link state, object) of every object the collection links, first-level states inherited
    by nested objects (foreach_light_collection_object)."""
    for child, entry in zip(collection.children, collection.collection_children, strict=True):
        state = entry.light_linking.link_state
        for ob in child.all_objects:
            yield state, ob
    for ob, entry in zip(collection.objects, collection.collection_objects, strict=True):
        yield entry.light_linking.link_state, ob


@dataclass(frozen=True)
class Links:
    """What an exported instance or lamp carries (native scene/light_links.h)."""

    receiver_light_set: int = 0
    blocker_shadow_set: int = 0
    light_set_membership: int = ALL_SETS
    shadow_set_membership: int = ALL_SETS


NO_LINKS = Links()


class LinkingSets:
    """The scene's light and shadow linking sets; links() gives an exported object's."""

    def __init__(self, light: _Linking, shadow: _Linking) -> None:
        self._light = light
        self._shadow = shadow

    def links(self, ob: Any, parent: Any | None = None) -> Links:
        """The sets of `ob` (an evaluated object or instance object), instanced by `parent`
        (None for an object drawn by itself)."""
        original = ob.original
        key = original.as_pointer()
        receiver = self._light.object_set.get(key, 0)
        blocker = self._shadow.object_set.get(key, 0)
        if parent is not None:
            parent_key = parent.original.as_pointer()
            receiver = self._light.object_set.get(parent_key, 0) or receiver
            blocker = self._shadow.object_set.get(parent_key, 0) or blocker
        linking = original.light_linking
        return Links(receiver, blocker, _membership(self._light, linking.receiver_collection),
                     _membership(self._shadow, linking.blocker_collection))

    def key(self) -> tuple[Any, ...]:
        """Comparable summary: equal keys give equal links for every object."""
        return tuple(tuple(sorted(d.items())) for linking in (self._light, self._shadow)
                     for d in (linking.object_set, linking.membership))


def _membership(linking: _Linking, collection: Any | None) -> int:
    if collection is None:
        return ALL_SETS
    return linking.membership.get(collection.original.as_pointer(), ALL_SETS)


def linking_sets(depsgraph: Any) -> LinkingSets | None:
    """The sets of the depsgraph's objects, or None when no object links (or Blender has no
    light linking: 3.x)."""
    light, shadow = _Linking(), _Linking()
    for ob in depsgraph.objects:
        linking = getattr(ob.original, "light_linking", None)
        if linking is None:
            return None  # Blender < 4.0: the property does not exist on any object
        if linking.receiver_collection is not None:
            light.add_emitter(linking.receiver_collection.original)
        if linking.blocker_collection is not None:
            shadow.add_emitter(linking.blocker_collection.original)
    if not light.collection_bit and not shadow.collection_bit:
        return None
    light.end_build()
    shadow.end_build()
    return LinkingSets(light, shadow)
