"""Weights through a shader graph, each node visited once (pure Python).

    order, weights = propagate(root, weight, inputs_of, on_cycle)

A Mix Shader scales its two inputs by (1 - Fac) and Fac, an Add Shader passes its weight to
both: the closures a node contributes scale linearly with the weight arriving at it. So the
weight of a node is the sum over every path from the output of the product of the factors
along the path, and one closure with that summed weight renders what one closure per path
would. Computing the sums in topological order visits each node once: the work is linear in
the node count, where a walk per path is exponential in a graph that shares inputs (n Add
Shaders that each take the one below on both inputs: 2^n paths) and recursive in its depth.
"""

from __future__ import annotations

from collections.abc import Callable, Hashable
from typing import TypeVar

Rgb = tuple[float, float, float]
K = TypeVar("K", bound=Hashable)


def propagate(root: K, weight: Rgb, inputs_of: Callable[[K], list[tuple[K, float]]],
              on_cycle: Callable[[K, K], None]) -> tuple[list[K], dict[K, Rgb]]:
    """Every node reachable from `root` in depth-first pre-order (first input first, so a tree
    gives its leaves left to right) and its summed weight. inputs_of(node) lists the node's
    inputs with the factor each scales the weight by; it is called once per node. A link
    from `node` back to `child` on the current path (a cycle) is dropped after
    on_cycle(child, node)."""
    inputs = {root: inputs_of(root)}
    order, finished = [root], []
    on_path = {root}
    stack = [(root, 0)]
    while stack:  # iterative: no recursion limit on deep graphs
        node, i = stack[-1]
        if i == len(inputs[node]):
            stack.pop()
            on_path.discard(node)
            finished.append(node)
            continue
        child = inputs[node][i][0]
        if child in on_path:
            on_cycle(child, node)
            del inputs[node][i]
            continue
        stack[-1] = (node, i + 1)
        if child not in inputs:
            inputs[child] = inputs_of(child)
            order.append(child)
            on_path.add(child)
            stack.append((child, 0))
    weights: dict[K, Rgb] = {root: weight}
    # Reverse finishing order is a topological order of the (now acyclic) graph: a node's
    # weight is complete before it is passed on. A tree's weights are the plain products
    # along its paths (the first addition is to nothing).
    for node in reversed(finished):
        here = weights[node]
        for child, factor in inputs[node]:
            add = (here[0] * factor, here[1] * factor, here[2] * factor)
            before = weights.get(child)
            weights[child] = add if before is None else (before[0] + add[0], before[1] + add[1],
                                                         before[2] + add[2])
    return order, weights
