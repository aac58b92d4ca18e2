"""Cycles measured: each module renders small scenes in Cycles (Blender 3.4, or the bpy wheel)
and prints or writes values that tests now hold as their reference. Run one again when a
Blender version changes the model, and update the test with what it reports.

| module           | measured                               | held by (tests/native/ if no path)  |
|------------------|----------------------------------------|-------------------------------------|
| sky.py           | Sky Texture pixels of every sky type   | test_sky_nodes.cpp,                 |
|                  |                                        | tests/python/test_sky_nodes.py      |
| noise.py         | Noise and Musgrave at exact points     | test_noise_nodes.cpp                |
| conventions.py   | material and light conventions (image  | test_bsdf.cpp                       |
|                  | means, docs/cycles_models.md)          | (DirectionalAlbedoMatchesCycles)    |
| principled_v2.py | Principled v2's directional albedo     | test_bsdf.cpp                       |
|                  | (Blender 5.0)                          | (V2DirectionalAlbedoMatchesCycles50)|

The other one-off probes (Voronoi and White Noise, the vector and converter nodes, the pattern
and Image nodes, the sky against Stratum, the sun disc's energy in a baked world) were removed:
their figures stay in docs/shader_nodes.md and in git history, and what they measured is
checked by tests/blender/test_node_agreement.py (every node against Cycles, per pixel, in each
Blender) and by the sky tests above (BakedWorldKeepsTheSunDiscsIrradiance for the disc).
"""
