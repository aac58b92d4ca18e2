"""The checkout's add-on driven through Blender from the command line: `make render`
(render_to_files.py: a .blend to PNG and EXR) and `make profile` (profile_render.sh, which
captures a .blend with capture_scene.py and runs the native CLI under perf)."""
