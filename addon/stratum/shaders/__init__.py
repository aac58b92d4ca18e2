"""Blender's shader node trees -> what the renderer takes: weighted native closures, the image
textures that drive their parameters, and node programs (pure Python, no bpy: nodes are read
by duck typing, so the unit tests use plain objects).

    surface.py    a material's surface tree -> closures (flatten_surface): the Mix and Add
                  Shader walk; flow.py sums the weights of the paths reaching each node
    closures.py   a closure node (BSDF, Emission, Holdout, Principled) -> native closures
    inputs.py     a closure node's inputs: clamped values, image bindings, program inputs
    records.py    what flattening produces (Closure, Binding, ProgramInput, ClosureWeight)
    fallbacks.py  Cycles' clamps of invalid values (materials, lights, world)
    nodes/        any node graph -> one node program (NodeCompiler, a translator per node)

The exporter (stratum.export: materials.py, world.py, light_nodes.py) feeds it Blender's
trees; stratum.blender_versions says which socket names and Cycles behaviour apply.
"""
