"""`make bench`: Stratum against Cycles, each section a module that writes out/bench/<section>.json
(results.py: the pure half, no bpy), summary.py the table of every figure at the end. Most run
inside Blender (scripts/run_in_blender.py); textures, distributed_render and summary under the
venv's Python. common.py is the Blender side they share."""
